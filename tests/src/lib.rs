//! End-to-end tests of the `raygine` binary live in `tests/tests/`.
