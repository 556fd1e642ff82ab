//! Property tests run the same cases on every machine: a fixed seed, so that CI tests what was
//! tested before a commit. `PROPTEST_RNG_SEED=random` (or a number) and `PROPTEST_CASES` ask for
//! a different or a longer run.

// Each test binary uses what it needs of the common module.
#![allow(dead_code)]

use proptest::test_runner::{Config, RngSeed};

/// The seed of the regular suite.
pub const SEED: u64 = 20_261_201;

/// A proptest configuration of `cases` cases with the fixed seed, unless the environment asks
/// for others.
pub fn config(cases: u32) -> Config {
    let from_env = Config::default();
    let seed = match std::env::var("PROPTEST_RNG_SEED") {
        Ok(_) => from_env.rng_seed,
        Err(_) => RngSeed::Fixed(SEED),
    };
    let cases = if std::env::var_os("PROPTEST_CASES").is_some() {
        from_env.cases
    } else {
        cases
    };
    Config {
        cases,
        rng_seed: seed,
        ..from_env
    }
}
