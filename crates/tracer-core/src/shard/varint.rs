//! The integers of a part's payload as variable-length numbers (LEB128, signed ones zigzag
//! encoded): a pixel's sums are mostly far below the i128 range, so a part takes about a third
//! of the space of fixed-width numbers.

/// Appends numbers to a byte buffer.
#[derive(Debug, Default)]
pub struct Encoder {
    pub bytes: Vec<u8>,
}

impl Encoder {
    pub fn u128(&mut self, mut v: u128) {
        loop {
            let low = (v & 0x7f) as u8;
            v >>= 7;
            if v == 0 {
                self.bytes.push(low);
                return;
            }
            self.bytes.push(low | 0x80);
        }
    }

    pub fn u64(&mut self, v: u64) {
        self.u128(u128::from(v));
    }

    pub fn u32(&mut self, v: u32) {
        self.u128(u128::from(v));
    }

    pub fn i128(&mut self, v: i128) {
        // Zigzag: 0, -1, 1, -2, ... -> 0, 1, 2, 3, ...
        self.u128(((v << 1) ^ (v >> 127)) as u128);
    }

    pub fn f32(&mut self, v: f32) {
        self.u32(v.to_bits());
    }

    pub fn str(&mut self, s: &str) {
        self.u64(s.len() as u64);
        self.bytes.extend_from_slice(s.as_bytes());
    }
}

/// Reads numbers back; every read is None at the end of the data or on a malformed number.
#[derive(Debug)]
pub struct Decoder<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl<'a> Decoder<'a> {
    pub fn new(bytes: &'a [u8]) -> Self {
        Self { bytes, at: 0 }
    }

    pub fn u128(&mut self) -> Option<u128> {
        let mut v = 0u128;
        for shift in (0..128).step_by(7) {
            let b = *self.bytes.get(self.at)?;
            self.at += 1;
            let bits = u128::from(b & 0x7f);
            if shift == 126 && bits > 0b11 {
                return None;
            }
            v |= bits << shift;
            if b & 0x80 == 0 {
                return Some(v);
            }
        }
        None
    }

    pub fn u64(&mut self) -> Option<u64> {
        u64::try_from(self.u128()?).ok()
    }

    pub fn u32(&mut self) -> Option<u32> {
        u32::try_from(self.u128()?).ok()
    }

    pub fn i128(&mut self) -> Option<i128> {
        let z = self.u128()?;
        Some(((z >> 1) as i128) ^ -((z & 1) as i128))
    }

    pub fn f32(&mut self) -> Option<f32> {
        Some(f32::from_bits(self.u32()?))
    }

    pub fn str(&mut self) -> Option<String> {
        let len = usize::try_from(self.u64()?).ok()?;
        let end = self.at.checked_add(len)?;
        let s = std::str::from_utf8(self.bytes.get(self.at..end)?).ok()?;
        self.at = end;
        Some(s.to_owned())
    }

    /// Whether every byte was read.
    pub fn is_at_end(&self) -> bool {
        self.at == self.bytes.len()
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use super::*;

    #[test]
    fn numbers_round_trip_at_the_edges_of_their_range() {
        let signed = [
            0,
            1,
            -1,
            63,
            -64,
            64,
            i128::from(i64::MAX),
            i128::MIN,
            i128::MAX,
        ];
        let mut e = Encoder::default();
        for v in signed {
            e.i128(v);
        }
        e.u32(u32::MAX);
        e.f32(-0.0);
        e.str("floor_1");
        let mut d = Decoder::new(&e.bytes);
        for v in signed {
            assert_eq!(d.i128(), Some(v));
        }
        assert_eq!(d.u32(), Some(u32::MAX));
        assert_eq!(d.f32().map(f32::to_bits), Some((-0.0f32).to_bits()));
        assert_eq!(d.str().as_deref(), Some("floor_1"));
        assert!(d.is_at_end());
        assert_eq!(d.u32(), None);
    }

    #[test]
    fn small_numbers_take_one_byte_and_malformed_ones_are_refused() {
        let mut e = Encoder::default();
        e.i128(-3);
        assert_eq!(e.bytes, [5]);
        assert_eq!(Decoder::new(&[0x80, 0x80]).u128(), None);
        assert_eq!(Decoder::new(&[0xff; 19]).u128(), None);
        assert_eq!(Decoder::new(&[0x80, 0x80, 0x80, 0x80, 0x10]).u32(), None);
    }
}
