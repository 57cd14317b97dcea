//! Drawing pavings and phase portraits (SVG and PNG).
