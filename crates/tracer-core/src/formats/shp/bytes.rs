//! Byte-level scanning for the lexer: line breaks found eight bytes at a time, whole numbers,
//! and short excerpts of arbitrary input for messages.

/// The index of the first LF, CR or `;` in `bytes`, eight bytes at a time: parsing time is
/// mostly spent finding line ends.
pub(super) fn find_break_or_semicolon(bytes: &[u8]) -> Option<usize> {
    const ONES: u64 = u64::from_le_bytes([0x01; 8]);
    const HIGHS: u64 = u64::from_le_bytes([0x80; 8]);
    // High bit set in the lowest byte equal to `byte` (higher ones may be false positives).
    let zero_bytes = |word: u64, byte: u8| {
        let x = word ^ (ONES * u64::from(byte));
        x.wrapping_sub(ONES) & !x & HIGHS
    };
    let chunks = bytes.chunks_exact(8);
    let tail = chunks.remainder();
    for (i, chunk) in chunks.enumerate() {
        let mut word = [0u8; 8];
        word.copy_from_slice(chunk);
        let word = u64::from_le_bytes(word);
        let hits = zero_bytes(word, b'\n') | zero_bytes(word, b'\r') | zero_bytes(word, b';');
        if hits != 0 {
            return Some(i * 8 + (hits.trailing_zeros() / 8) as usize);
        }
    }
    let tail_start = bytes.len() - tail.len();
    tail.iter()
        .position(|b| matches!(b, b'\n' | b'\r' | b';'))
        .map(|k| tail_start + k)
}

/// At most 60 characters of `text`, for messages about arbitrary input.
pub(crate) fn excerpt(text: &str) -> String {
    const MAX_CHARS: usize = 60;
    match text.char_indices().nth(MAX_CHARS) {
        Some((end, _)) => format!("{}...", &text[..end]),
        None => text.to_string(),
    }
}

/// A decimal whole number with optional `+`; `-0` (any number of zeros) reads as 0.
pub(crate) fn parse_u32(token: &str) -> Option<u32> {
    let digits = match token.as_bytes() {
        [b'+', rest @ ..] => rest,
        [b'-', rest @ ..] if !rest.is_empty() && rest.iter().all(|&b| b == b'0') => return Some(0),
        all => all,
    };
    if digits.is_empty() {
        return None;
    }
    let mut value: u32 = 0;
    for &b in digits {
        let digit = b.wrapping_sub(b'0');
        if digit > 9 {
            return None;
        }
        value = value.checked_mul(10)?.checked_add(u32::from(digit))?;
    }
    Some(value)
}
