//! Helpers shared by the crate's unit tests (compiled for tests only).

pub(crate) mod chi2;
