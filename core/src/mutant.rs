//! CI's guarded mutations from one build (issue 36): `mutant!("name", original, broken)` is `original`
//! in every ordinary build. Built with the `mutants` feature, it is `broken` in a process whose
//! `ACCELCAL_MUTANT` names it, and `original` otherwise. `host/tools/guarded_mutations.py` builds the
//! tests of the core and the host once with the feature and runs each guard test with its mutation named, so that no source
//! file is edited and nothing is recompiled per mutation; docs/mutations.md lists every one.

/// The environment variable that names the one mutation a process runs with.
#[cfg(feature = "mutants")]
pub const VARIABLE: &str = "ACCELCAL_MUTANT";

/// Whether `ACCELCAL_MUTANT` names `name` (read once, on the first mutant a process meets).
#[cfg(feature = "mutants")]
pub fn active(name: &str) -> bool {
    static NAMED: std::sync::OnceLock<Option<String>> = std::sync::OnceLock::new();
    NAMED.get_or_init(|| std::env::var(VARIABLE).ok()).as_deref() == Some(name)
}

/// `original`, or with the `mutants` feature `broken` while `ACCELCAL_MUTANT` names `name`.
#[cfg(feature = "mutants")]
#[macro_export]
macro_rules! mutant {
    ($name:literal, $original:expr, $broken:expr $(,)?) => {
        if $crate::mutant::active($name) {
            $broken
        } else {
            $original
        }
    };
}

/// `original`: the build without the `mutants` feature carries no broken line.
#[cfg(not(feature = "mutants"))]
#[macro_export]
macro_rules! mutant {
    ($name:literal, $original:expr, $broken:expr $(,)?) => {
        $original
    };
}
