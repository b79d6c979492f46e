//! Errors that reach the user. Every load error names the file and, where one exists, the line,
//! the XML element or the byte offset where the input went wrong.

use std::fmt;

/// Where in an input file a problem was found.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Location {
    /// The file as a whole (empty scene, unknown format, ...).
    File,
    /// A 1-based line of a text file.
    Line(usize),
    /// An XML element, with the 1-based line it starts on.
    Element { name: String, line: usize },
    /// A byte offset into a binary file.
    Byte(u64),
}

/// A file could not be turned into a scene.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LoadError {
    pub file: String,
    pub location: Location,
    pub message: String,
}

impl LoadError {
    pub fn new(file: &str, location: Location, message: impl Into<String>) -> Self {
        LoadError {
            file: file.to_string(),
            location,
            message: message.into(),
        }
    }
    pub fn file(file: &str, message: impl Into<String>) -> Self {
        Self::new(file, Location::File, message)
    }
    pub fn line(file: &str, line: usize, message: impl Into<String>) -> Self {
        Self::new(file, Location::Line(line), message)
    }
    pub fn byte(file: &str, offset: u64, message: impl Into<String>) -> Self {
        Self::new(file, Location::Byte(offset), message)
    }
    pub fn element(file: &str, name: &str, line: usize, message: impl Into<String>) -> Self {
        Self::new(
            file,
            Location::Element {
                name: name.to_string(),
                line,
            },
            message,
        )
    }
}

impl fmt::Display for LoadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.location {
            Location::File => write!(f, "{}: {}", self.file, self.message),
            Location::Line(line) => write!(f, "{}:{}: {}", self.file, line, self.message),
            Location::Element { name, line } => {
                write!(f, "{}:{}: <{}>: {}", self.file, line, name, self.message)
            }
            Location::Byte(offset) => {
                write!(f, "{}: at byte {}: {}", self.file, offset, self.message)
            }
        }
    }
}

impl std::error::Error for LoadError {}

/// Any error the library reports.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    #[error(transparent)]
    Load(#[from] LoadError),
    #[error("{0}")]
    Camera(String),
    #[error("{path}: {source}")]
    Io {
        path: String,
        #[source]
        source: std::io::Error,
    },
    #[error("{0}")]
    Output(String),
}

pub type Result<T, E = Error> = std::result::Result<T, E>;
