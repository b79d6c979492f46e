//! Scene analysis (not yet written).
