//! Figures as they are printed: one `KIND key=value ...` line per figure (flushed at once, so a
//! long run shows progress) and markdown tables at the end.

use std::io::Write;

/// One measured figure of a library on a mesh.
#[derive(Clone, Debug, PartialEq)]
pub struct Figure {
    /// `build`, `W1`, `W2`, `W3`.
    pub kind: String,
    pub mesh: String,
    pub lib: String,
    pub threads: usize,
    /// Milliseconds for `build`, Mrays/s for workloads.
    pub value: f64,
}

impl Figure {
    /// The figure's line, e.g. `W1 mesh=stanford-bunny lib=raygine threads=2 mrays=14.2`.
    pub fn line(&self) -> String {
        let (key, value) = if self.kind == "build" {
            ("ms", format!("{:.0}", self.value))
        } else {
            ("mrays", format!("{:.2}", self.value))
        };
        format!(
            "{} mesh={} lib={} threads={} {key}={value}",
            self.kind, self.mesh, self.lib, self.threads
        )
    }

    /// Higher is better for throughput, lower for build time.
    pub fn is_time(&self) -> bool {
        self.kind == "build"
    }
}

/// Prints a line and flushes stdout.
pub fn emit(line: &str) {
    let mut out = std::io::stdout().lock();
    let _ = writeln!(out, "{line}");
    let _ = out.flush();
}

/// The figure for (kind, mesh, lib, threads), if measured.
pub fn find<'a>(
    figures: &'a [Figure],
    kind: &str,
    mesh: &str,
    lib: &str,
    threads: usize,
) -> Option<&'a Figure> {
    figures
        .iter()
        .find(|f| f.kind == kind && f.mesh == mesh && f.lib == lib && f.threads == threads)
}

/// raygine's speed relative to a peer: > 1 means raygine is faster (Mrays/s ratio for workloads,
/// inverse time ratio for builds).
pub fn speed_ratio(raygine: &Figure, peer: &Figure) -> f64 {
    if raygine.is_time() {
        peer.value / raygine.value
    } else {
        raygine.value / peer.value
    }
}

/// Distinct values in first-seen order.
pub fn distinct<T: PartialEq + Clone>(items: impl IntoIterator<Item = T>) -> Vec<T> {
    let mut out: Vec<T> = Vec::new();
    for item in items {
        if !out.contains(&item) {
            out.push(item);
        }
    }
    out
}

/// A markdown table of every figure, one row per (mesh, threads, kind), one column per library,
/// plus raygine's speed ratio to every other library.
pub fn table(figures: &[Figure]) -> String {
    let libs = distinct(figures.iter().map(|f| f.lib.clone()));
    let peers: Vec<&String> = libs.iter().filter(|l| *l != "raygine").collect();
    let mut out = String::from("| mesh | threads | figure |");
    for lib in &libs {
        out += &format!(" {lib} |");
    }
    for peer in &peers {
        out += &format!(" raygine/{peer} |");
    }
    out += "\n|---|---|---|";
    out += &"---|".repeat(libs.len() + peers.len());
    out += "\n";
    let keys = distinct(
        figures
            .iter()
            .map(|f| (f.mesh.clone(), f.threads, f.kind.clone())),
    );
    for (mesh, threads, kind) in keys {
        let unit = if kind == "build" { "ms" } else { "Mrays/s" };
        out += &format!("| {mesh} | {threads} | {kind} {unit} |");
        for lib in &libs {
            match find(figures, &kind, &mesh, lib, threads) {
                Some(f) if f.is_time() => out += &format!(" {:.0} |", f.value),
                Some(f) => out += &format!(" {:.2} |", f.value),
                None => out += " - |",
            }
        }
        for peer in &peers {
            let own = find(figures, &kind, &mesh, "raygine", threads);
            let other = find(figures, &kind, &mesh, peer, threads);
            match own.zip(other) {
                Some((a, b)) => out += &format!(" {:.2} |", speed_ratio(a, b)),
                None => out += " - |",
            }
        }
        out += "\n";
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fig(kind: &str, lib: &str, value: f64) -> Figure {
        Figure {
            kind: kind.into(),
            mesh: "stanford-bunny".into(),
            lib: lib.into(),
            threads: 2,
            value,
        }
    }

    #[test]
    fn lines_have_the_documented_form() {
        assert_eq!(
            fig("W1", "raygine", 14.2).line(),
            "W1 mesh=stanford-bunny lib=raygine threads=2 mrays=14.20"
        );
        assert_eq!(
            fig("build", "raygine", 85.4).line(),
            "build mesh=stanford-bunny lib=raygine threads=2 ms=85"
        );
    }

    #[test]
    fn ratios_say_faster_above_one() {
        assert_eq!(
            speed_ratio(&fig("W1", "raygine", 20.0), &fig("W1", "embree", 10.0)),
            2.0
        );
        assert_eq!(
            speed_ratio(
                &fig("build", "raygine", 50.0),
                &fig("build", "embree", 100.0)
            ),
            2.0
        );
    }

    #[test]
    fn table_has_a_ratio_column_per_peer() {
        let t = table(&[fig("W1", "raygine", 20.0), fig("W1", "embree", 10.0)]);
        assert!(t.contains("raygine/embree"));
        assert!(t.contains("| stanford-bunny | 2 | W1 Mrays/s | 20.00 | 10.00 | 2.00 |"));
    }
}
