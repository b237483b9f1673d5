//! Built-in robots.
