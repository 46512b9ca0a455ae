//! The toolpath study: five-axis toolpaths read from CSV, APT CL data or NC blocks ([`parse`]).

pub mod parse;
