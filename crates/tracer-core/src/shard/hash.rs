//! A stable 64-bit hash (FNV-1a): the same bytes give the same number on every machine, build
//! and run, unlike `std`'s randomly keyed hashers. Used to tell parts of one scene and setup from
//! parts of another, and as the checksum of a part's bytes.

use crate::scene::{Scene, Setup};

const FNV_OFFSET: u64 = 0xcbf2_9ce4_8422_2325;
const FNV_PRIME: u64 = 0x0000_0100_0000_01b3;

/// FNV-1a over a stream of bytes.
#[derive(Clone, Copy, Debug)]
pub struct StableHash(u64);

impl Default for StableHash {
    fn default() -> Self {
        Self(FNV_OFFSET)
    }
}

impl StableHash {
    pub fn new() -> Self {
        Self::default()
    }

    pub fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 = (self.0 ^ u64::from(b)).wrapping_mul(FNV_PRIME);
        }
    }

    pub fn write_u32(&mut self, v: u32) {
        self.write(&v.to_le_bytes());
    }

    pub fn finish(&self) -> u64 {
        self.0
    }

    /// The hash of `bytes` alone.
    pub fn of(bytes: &[u8]) -> u64 {
        let mut h = Self::new();
        h.write(bytes);
        h.finish()
    }
}

/// The hash of what a render or a measurement of `scene` with `setup` depends on: every
/// triangle's vertices (bit for bit) and material slot, and the whole setup (camera, lights with
/// their photometric tables, materials, hidden slots, grids, unit, handedness, maintenance
/// factor). The setup enters through its `Debug` text, which prints every field and every float
/// exactly (shortest round-trip form), so a field added to a material or a light later is
/// covered without changing this function. Glowing-surface tables are built from these.
pub fn scene_hash(scene: &Scene, setup: &Setup) -> u64 {
    let mut h = StableHash::new();
    h.write(b"triangles");
    let own = scene.own_triangle_count();
    h.write(&(own as u64).to_le_bytes());
    for t in 0..own as u32 {
        for v in scene.triangle(t) {
            for c in v.to_array() {
                h.write_u32(c.to_bits());
            }
        }
        h.write_u32(scene.slot(t));
    }
    // Reused meshes once each, and each instance's placement and slots.
    let instances = scene.instances();
    if !instances.is_empty() {
        h.write(b"prototypes");
        for p in &instances.prototypes {
            h.write(&(p.set.len() as u64).to_le_bytes());
            for (t, part) in p.set.slots.iter().enumerate() {
                for v in p.bvh.triangle(t) {
                    for c in v.to_array() {
                        h.write_u32(c.to_bits());
                    }
                }
                h.write_u32(*part);
            }
        }
        h.write(b"instances");
        for i in &instances.instances {
            h.write_u32(i.prototype);
            h.write_u32(i.first_slot);
            for c in i.world_from_local.to_cols_array() {
                h.write_u32(c.to_bits());
            }
        }
    }
    h.write(b"slots");
    for owner in &scene.slots {
        h.write_u32(owner.brep);
        h.write_u32(owner.part);
    }
    h.write(b"setup");
    h.write(format!("{setup:?}").as_bytes());
    h.finish()
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use super::*;

    #[test]
    fn fnv1a_matches_the_published_test_vectors() {
        assert_eq!(StableHash::of(b""), 0xcbf2_9ce4_8422_2325);
        assert_eq!(StableHash::of(b"a"), 0xaf63_dc4c_8601_ec8c);
        assert_eq!(StableHash::of(b"foobar"), 0x8594_4171_f739_67e8);
    }

    #[test]
    fn the_scene_hash_sees_lights_and_materials() {
        let loaded = crate::scene::builtin_cornell_box(None).unwrap();
        let base = scene_hash(&loaded.scene, &loaded.setup);
        assert_eq!(base, scene_hash(&loaded.scene, &loaded.setup.clone()));
        let mut moved = loaded.setup.clone();
        moved.lights[0].position[0] += 1.0;
        assert_ne!(base, scene_hash(&loaded.scene, &moved));
        let mut red = loaded.setup.clone();
        red.materials[0].kd[1] *= 0.5;
        assert_ne!(base, scene_hash(&loaded.scene, &red));
    }
}
