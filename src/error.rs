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
    Element {
        /// The element's tag name.
        name: String,
        /// The 1-based line the element starts on.
        line: usize,
    },
    /// A byte offset into a binary file.
    Byte(u64),
}

/// A file could not be turned into a scene.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LoadError {
    /// The file, as the user named it.
    pub file: String,
    /// Where in the file.
    pub location: Location,
    /// What is wrong there.
    pub message: String,
}

impl LoadError {
    /// An error at `location` of `file`.
    pub fn new(file: &str, location: Location, message: impl Into<String>) -> Self {
        LoadError {
            file: file.to_string(),
            location,
            message: message.into(),
        }
    }
    /// An error about `file` as a whole.
    pub fn file(file: &str, message: impl Into<String>) -> Self {
        Self::new(file, Location::File, message)
    }
    /// An error at a 1-based line of a text file.
    pub fn line(file: &str, line: usize, message: impl Into<String>) -> Self {
        Self::new(file, Location::Line(line), message)
    }
    /// An error at a byte offset of a binary file.
    pub fn byte(file: &str, offset: u64, message: impl Into<String>) -> Self {
        Self::new(file, Location::Byte(offset), message)
    }
    /// An error at an XML element (`name`) starting on a 1-based line.
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
    /// An input file could not be turned into a scene.
    #[error(transparent)]
    Load(#[from] LoadError),
    /// The camera asked for defines no proper view.
    #[error("{0}")]
    Camera(String),
    /// Reading or writing a file failed.
    #[error("{path}: {source}")]
    Io {
        /// The file, as the user named it.
        path: String,
        /// What the system said.
        #[source]
        source: std::io::Error,
    },
    /// The output cannot be written as asked (unknown extension, binary data to a terminal).
    #[error("{0}")]
    Output(String),
    /// Options that contradict each other, that the output would ignore, or out of range (see
    /// [`crate::render::RenderOptions::check`]); the message names the command line's flags.
    #[error("{0}")]
    Options(String),
}

/// A result whose error is [`Error`].
pub type Result<T, E = Error> = std::result::Result<T, E>;
