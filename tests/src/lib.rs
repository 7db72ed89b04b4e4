//! End-to-end tests of ldh: `tests/*.rs` run the `ldh` command (the `ldh-under-test` binary is
//! `ldh_cli::run`, the same code as `ldh`) on simulated cohorts and check files, messages and
//! exit codes.
