//! The "too large for memory" check: declared counts are turned into an estimate of what the
//! built scene will need (description, world triangles, BVH), and a file that cannot fit in the
//! memory the machine has available is refused when its count is read, before anything is
//! allocated, instead of aborting the process half-way through a multi-gigabyte load.

use std::path::Path;

use super::error::ShpError;

/// Estimated bytes per triangle from file to rendered scene: indices and part (16 in the
/// description), world positions (36), normal (12), slot (4), BVH nodes and references and the
/// build's scratch (about 130).
pub(crate) const BYTES_PER_TRIANGLE: u64 = 200;
/// Estimated bytes per vertex: 24 in the description, 12 as a world position, slack.
pub(crate) const BYTES_PER_VERTEX: u64 = 40;
/// Below this estimate the available memory is not even looked up (small files cost nothing).
const CHECK_FROM_BYTES: u64 = 256 << 20;

/// The memory a file's declared counts add up to so far, against what the machine has.
#[derive(Debug)]
pub(crate) struct MemoryBudget {
    declared_bytes: u64,
    /// Available bytes: `None` until looked up, `Some(None)` where the platform does not say.
    available: Option<Option<u64>>,
}

impl MemoryBudget {
    /// A budget that asks the operating system when a file turns out to be big.
    pub fn from_system() -> Self {
        Self {
            declared_bytes: 0,
            available: None,
        }
    }

    /// A budget with a fixed number of available bytes (for tests).
    #[cfg(test)]
    pub fn with_available(bytes: u64) -> Self {
        Self {
            declared_bytes: 0,
            available: Some(Some(bytes)),
        }
    }

    /// Adds `count` items of `bytes_each` declared by `keyword` on line `line_no`; an error when
    /// the total would exceed the available memory.
    pub fn declare(
        &mut self,
        path: &Path,
        line_no: usize,
        keyword: &str,
        count: u32,
        bytes_each: u64,
    ) -> Result<(), ShpError> {
        let total = self
            .declared_bytes
            .saturating_add(u64::from(count).saturating_mul(bytes_each));
        if total >= CHECK_FROM_BYTES {
            let available = *self.available.get_or_insert_with(available_memory_bytes);
            if let Some(available) = available.filter(|&a| total > a) {
                return Err(ShpError::TooLargeForMemory {
                    path: path.to_path_buf(),
                    line: line_no,
                    keyword: keyword.to_string(),
                    count,
                    needed: gigabytes(total),
                    available: gigabytes(available),
                });
            }
        }
        self.declared_bytes = total;
        Ok(())
    }
}

/// `12.3 GB`, for messages (decimal gigabytes, one decimal).
fn gigabytes(bytes: u64) -> String {
    format!("{:.1} GB", bytes as f64 / 1e9)
}

/// `MemAvailable` of `/proc/meminfo` on Linux: memory that can be had without swapping.
/// `None` elsewhere, or when the file cannot be read, which turns the check off.
pub(crate) fn available_memory_bytes() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    parse_mem_available(&text)
}

/// The `MemAvailable:  123456 kB` line of `/proc/meminfo`, in bytes.
fn parse_mem_available(meminfo: &str) -> Option<u64> {
    let line = meminfo
        .lines()
        .find_map(|l| l.strip_prefix("MemAvailable:"))?;
    let mut words = line.split_ascii_whitespace();
    let value: u64 = words.next()?.parse().ok()?;
    let unit = match words.next() {
        Some("kB") => 1024,
        None => 1,
        Some(_) => return None,
    };
    value.checked_mul(unit)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use super::*;

    #[test]
    fn reads_mem_available() {
        let meminfo =
            "MemTotal:       24000000 kB\nMemFree:  100 kB\nMemAvailable:   20000000 kB\n";
        assert_eq!(parse_mem_available(meminfo), Some(20_000_000 * 1024));
        assert_eq!(parse_mem_available("MemTotal: 5 kB\n"), None);
        assert_eq!(parse_mem_available("MemAvailable: x kB\n"), None);
    }

    #[test]
    fn budget_adds_up_counts_and_refuses_past_the_available_memory() {
        let path = Path::new("big.shp");
        let keyword = "triangles";
        let mut budget = MemoryBudget::with_available(1 << 30);
        // 3 million triangles: 600 MB, fits in 1 GiB.
        budget
            .declare(path, 7, keyword, 3_000_000, BYTES_PER_TRIANGLE)
            .unwrap();
        // Another 3 million do not.
        let err = budget
            .declare(path, 7, keyword, 3_000_000, BYTES_PER_TRIANGLE)
            .unwrap_err();
        assert_eq!(
            err.to_string(),
            "big.shp: line 7: `triangles 3000000` makes the scene need about 1.2 GB of memory, \
             more than the 1.1 GB available"
        );
    }

    #[test]
    fn the_reader_refuses_a_count_past_the_budget_at_its_line() {
        use super::super::brep::BrepReader;
        use super::super::lexer::Lexer;
        // 1.4 million triangles (280 MB estimated) that the file really holds, against 200 MB.
        let count = 1_400_000;
        let mut text = String::from("vertices 3\n0 0 0\n1 0 0\n0 1 0\n;; many\n");
        text.push_str(&format!("triangles {count}\n"));
        text.push_str(&"0 1 2\n".repeat(count));
        let path = Path::new("big.brs");
        let read = |available: u64| {
            let mut lex = Lexer::new(text.as_bytes(), path).unwrap();
            lex.set_memory_budget(MemoryBudget::with_available(available));
            let mut reader = BrepReader::new("big".into(), path.to_path_buf(), 0);
            while let Some(line) = lex.next_line()? {
                reader.section(&mut lex, line)?;
            }
            Ok::<_, ShpError>(reader.finish())
        };
        let err = read(200_000_000).unwrap_err();
        assert!(
            matches!(err, ShpError::TooLargeForMemory { line: 6, .. }),
            "{err}"
        );
        assert_eq!(
            err.to_string(),
            "big.brs: line 6: `triangles 1400000` makes the scene need about 0.3 GB of memory, \
             more than the 0.2 GB available"
        );
        assert_eq!(read(1_000_000_000).unwrap().triangles.len(), count);
    }
}
