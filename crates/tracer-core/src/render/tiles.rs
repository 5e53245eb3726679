//! Image tiles, ordered from the image centre outwards so the middle of the picture comes first.

/// A rectangle of pixels, `x0..x1` by `y0..y1`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Tile {
    pub x0: u32,
    pub y0: u32,
    pub x1: u32,
    pub y1: u32,
}

impl Tile {
    pub fn width(&self) -> u32 {
        self.x1 - self.x0
    }

    pub fn height(&self) -> u32 {
        self.y1 - self.y0
    }

    pub fn pixel_count(&self) -> usize {
        self.width() as usize * self.height() as usize
    }

    /// Pixels in row-major order.
    pub fn pixels(&self) -> impl Iterator<Item = (u32, u32)> + use<> {
        let (x0, x1) = (self.x0, self.x1);
        (self.y0..self.y1).flat_map(move |y| (x0..x1).map(move |x| (x, y)))
    }
}

/// Tiles of `size` pixels covering the image, sorted by distance of their centre from the image
/// centre (ties broken by position, so the order is deterministic).
pub fn tiles_centre_out(width: u32, height: u32, size: u32) -> Vec<Tile> {
    let size = size.max(1);
    let mut tiles = Vec::new();
    for y0 in (0..height).step_by(size as usize) {
        for x0 in (0..width).step_by(size as usize) {
            tiles.push(Tile {
                x0,
                y0,
                x1: (x0 + size).min(width),
                y1: (y0 + size).min(height),
            });
        }
    }
    let (cx, cy) = (width as i64, height as i64);
    tiles.sort_by_key(|t| {
        let dx = i64::from(t.x0 + t.x1) - cx;
        let dy = i64::from(t.y0 + t.y1) - cy;
        (dx * dx + dy * dy, t.y0, t.x0)
    });
    tiles
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tiles_cover_every_pixel_once_centre_first() {
        let tiles = tiles_centre_out(100, 70, 16);
        let mut seen = vec![0u8; 100 * 70];
        for t in &tiles {
            for (x, y) in t.pixels() {
                seen[(y * 100 + x) as usize] += 1;
            }
        }
        assert!(seen.iter().all(|&c| c == 1));
        let first = tiles[0];
        assert!(first.x0 <= 50 && 50 <= first.x1 && first.y0 <= 35 && 35 <= first.y1);
    }
}
