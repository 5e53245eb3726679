//! Where the Open Image Denoise library is looked for, in order:
//!
//! 1. `RAYGINE_OIDN`: a library file, or a folder holding `libOpenImageDenoise.so.2`; `off`
//!    disables the denoiser;
//! 2. the system's library path (`libOpenImageDenoise.so.2` by name, as the dynamic loader finds
//!    it: `LD_LIBRARY_PATH`, `ldconfig`'s cache);
//! 3. the `lib` folder of a `pyoidn` wheel installed with pip: in the active virtual environment
//!    (`VIRTUAL_ENV`), in the user's site-packages, or where `python3` finds the package.

use std::path::{Path, PathBuf};

/// The library's file name on this platform (the 2.x ABI).
pub const LIBRARY_NAME: &str = if cfg!(target_os = "macos") {
    "libOpenImageDenoise.2.dylib"
} else if cfg!(windows) {
    "OpenImageDenoise.dll"
} else {
    "libOpenImageDenoise.so.2"
};

/// The environment variable that names the library (or `off`).
pub const ENV_VAR: &str = "RAYGINE_OIDN";

/// One place to try.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Candidate {
    /// A path to a library file.
    File(PathBuf),
    /// A bare name for the system's loader.
    System(&'static str),
}

impl std::fmt::Display for Candidate {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Candidate::File(p) => write!(f, "{}", p.display()),
            Candidate::System(name) => write!(f, "{name} (system library path)"),
        }
    }
}

/// What the search says before anything is loaded.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Search {
    /// `RAYGINE_OIDN=off`.
    Disabled,
    /// Try these, in order.
    Try(Vec<Candidate>),
}

/// The places to try, from the environment `var` (the value of `RAYGINE_OIDN`).
pub fn candidates(var: Option<&str>) -> Search {
    let mut out = Vec::new();
    if let Some(v) = var.map(str::trim).filter(|v| !v.is_empty()) {
        if v.eq_ignore_ascii_case("off") {
            return Search::Disabled;
        }
        let p = PathBuf::from(v);
        // A named place is the only one tried: a user who points at a library wants that one.
        return Search::Try(vec![Candidate::File(if p.is_dir() {
            p.join(LIBRARY_NAME)
        } else {
            p
        })]);
    }
    out.push(Candidate::System(LIBRARY_NAME));
    for dir in pyoidn_lib_dirs() {
        let file = dir.join(LIBRARY_NAME);
        if file.is_file() && !out.contains(&Candidate::File(file.clone())) {
            out.push(Candidate::File(file));
        }
    }
    Search::Try(out)
}

/// `lib` folders of pip-installed `pyoidn` wheels.
fn pyoidn_lib_dirs() -> Vec<PathBuf> {
    let mut sites = Vec::new();
    if let Some(venv) = std::env::var_os("VIRTUAL_ENV") {
        sites.extend(site_packages(&Path::new(&venv).join("lib")));
    }
    if let Some(home) = std::env::var_os("HOME") {
        sites.extend(site_packages(&Path::new(&home).join(".local/lib")));
    }
    if let Some(dir) = python_reports_pyoidn() {
        sites.push(dir);
    }
    sites
        .into_iter()
        .map(|s| {
            if s.ends_with("pyoidn") {
                s.join("oidn/lib")
            } else {
                s.join("pyoidn/oidn/lib")
            }
        })
        .collect()
}

/// `<lib>/python3.*/site-packages` folders.
fn site_packages(lib: &Path) -> Vec<PathBuf> {
    let Ok(entries) = std::fs::read_dir(lib) else {
        return Vec::new();
    };
    let mut out: Vec<PathBuf> = entries
        .flatten()
        .filter(|e| e.file_name().to_string_lossy().starts_with("python3"))
        .map(|e| e.path().join("site-packages"))
        .filter(|p| p.is_dir())
        .collect();
    out.sort();
    out
}

/// The folder of the `pyoidn` package as `python3` finds it (None without python3 or the
/// package). Asked once per search; Python prints the path and nothing else.
fn python_reports_pyoidn() -> Option<PathBuf> {
    let out = std::process::Command::new("python3")
        .args([
            "-c",
            "import importlib.util as u; s = u.find_spec('pyoidn'); \
             print(s.submodule_search_locations[0] if s else '')",
        ])
        .stdin(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .output()
        .ok()?;
    let text = String::from_utf8(out.stdout).ok()?;
    let dir = text.trim();
    (!dir.is_empty()).then(|| PathBuf::from(dir))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn off_disables_and_a_named_file_is_the_only_candidate() {
        assert_eq!(candidates(Some("off")), Search::Disabled);
        assert_eq!(candidates(Some(" OFF ")), Search::Disabled);
        assert_eq!(
            candidates(Some("/opt/x/libOpenImageDenoise.so.2.5.1")),
            Search::Try(vec![Candidate::File(PathBuf::from(
                "/opt/x/libOpenImageDenoise.so.2.5.1"
            ))])
        );
        let dir = std::env::temp_dir();
        assert_eq!(
            candidates(Some(dir.to_str().unwrap_or("/tmp"))),
            Search::Try(vec![Candidate::File(dir.join(LIBRARY_NAME))])
        );
    }

    #[test]
    fn without_the_variable_the_system_path_comes_first() {
        let Search::Try(c) = candidates(None) else {
            panic!("not disabled without the variable");
        };
        assert_eq!(c[0], Candidate::System(LIBRARY_NAME));
    }
}
