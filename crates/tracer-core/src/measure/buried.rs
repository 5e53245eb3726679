//! Grid points inside or under objects: a point whose every view of its hemisphere ends on the
//! back of a surface sits inside a closed object, such as a block standing on the floor the grid
//! crosses. Such a point reads 0 lx, which is no measurement of the lit room; it is shown
//! hatched and left out of the statistics.
//!
//! Which side of a surface is its front depends on the file's winding (Lumicept's left-handed
//! files wind the other way), so the front is taken as the side the camera sees: the winding of
//! most surfaces the camera's rays meet. A room's walls face its inside and a block's faces its
//! outside, so from a point in the room the walls show their fronts, from inside the block its
//! backs.

use super::SensorPoint;
use crate::geometry::Ray;
use crate::scene::Scene;
use glam::Vec3;

/// Directions tried per point (spread evenly over its hemisphere).
const DIRECTIONS: usize = 48;

/// The winding of the surfaces' fronts: +1 when the camera meets most surfaces with
/// (b − a) × (c − a) pointing along its ray, −1 when against it.
pub fn front_winding(scene: &Scene, setup: &crate::scene::Setup) -> f32 {
    let basis = setup.camera.basis(setup.handedness, 16, 16);
    let mut along = 0i32;
    for y in 0..16 {
        for x in 0..16 {
            let Some(ray) = basis.ray(x as f32 + 0.5, y as f32 + 0.5) else {
                continue;
            };
            if let Some(hit) = scene.closest_drawn(&ray, &setup.hidden) {
                let [a, b, c] = scene.triangle(hit.prim);
                along += if (b - a).cross(c - a).dot(ray.dir) > 0.0 {
                    1
                } else {
                    -1
                };
            }
        }
    }
    if along > 0 { 1.0 } else { -1.0 }
}

/// Whether `point` is enclosed: every direction over its hemisphere hits a surface, and nearly
/// all of those (all but one in twelve, for seams and grazing hits) on its back, the side
/// opposite to `front` (see [`front_winding`]).
pub fn is_buried(scene: &Scene, point: &SensorPoint, hidden: &[bool], front: f32) -> bool {
    let n = point.normal.normalize_or_zero();
    if n == Vec3::ZERO {
        return false;
    }
    let (t1, t2) = n.any_orthonormal_pair();
    let mut from_behind = 0;
    for k in 0..DIRECTIONS {
        // A Fibonacci spiral over the hemisphere, uniform in solid angle.
        let z = 1.0 - (k as f32 + 0.5) / DIRECTIONS as f32;
        let r = (1.0 - z * z).max(0.0).sqrt();
        let phi = k as f32 * 2.399_963;
        let dir = t1 * (r * phi.cos()) + t2 * (r * phi.sin()) + n * z;
        let Some(hit) = scene.closest_drawn(&Ray::new(point.position, dir), hidden) else {
            return false;
        };
        let [a, b, c] = scene.triangle(hit.prim);
        if (b - a).cross(c - a).dot(dir) * front < 0.0 {
            from_behind += 1;
        }
    }
    from_behind * 12 >= DIRECTIONS * 11
}

/// For each point of `points`, whether it is buried (see [`is_buried`]), the fronts taken from
/// what `setup`'s camera sees.
pub fn buried_points(
    scene: &Scene,
    setup: &crate::scene::Setup,
    points: &[SensorPoint],
) -> Vec<bool> {
    use rayon::prelude::*;
    let front = front_winding(scene, setup);
    points
        .par_iter()
        .map(|p| is_buried(scene, p, &setup.hidden, front))
        .collect()
}

/// Marks the points of `results` (one per grid of `setup`, in order) that are buried.
pub fn mark_buried(results: &mut [super::GridResult], scene: &Scene, setup: &crate::scene::Setup) {
    for (r, grid) in results.iter_mut().zip(&setup.grids) {
        let points: Vec<SensorPoint> = grid.points().collect();
        if points.len() != r.points.len() {
            continue;
        }
        for (p, b) in r
            .points
            .iter_mut()
            .zip(buried_points(scene, setup, &points))
        {
            p.buried = b;
        }
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    /// A work plane a quarter up the built-in box crosses its short block (165 mm tall) and its
    /// tall block: the points inside them, and only those, are buried.
    #[test]
    fn points_inside_the_boxs_blocks_are_buried_and_the_rest_not() {
        let loaded = crate::scene::builtin_cornell_box(None).unwrap();
        let scene = &loaded.scene;
        let b = scene.bounds;
        let grid = crate::measure::Grid::new(
            "plane",
            [b.min.x + 5.0, b.min.y + 0.25 * b.extent().y, b.min.z + 5.0],
            [b.extent().x - 10.0, 0.0, 0.0],
            [0.0, 0.0, b.extent().z - 10.0],
            24,
            24,
            Some([0.0, 1.0, 0.0]),
        )
        .unwrap();
        let points: Vec<SensorPoint> = grid.points().collect();
        let buried = buried_points(scene, &loaded.setup, &points);
        let count = buried.iter().filter(|&&b| b).count();
        eprintln!("{count} of {} buried", points.len());
        // Block footprints: about 165 x 165 mm each, of the 546 x 549 mm plane: 9 % each.
        let share = count as f64 / points.len() as f64;
        assert!(
            (0.12..0.25).contains(&share),
            "{count} of {} buried",
            points.len()
        );
        // A point inside a block meets the block's top when it looks straight up, well below
        // the ceiling; any other point sees the ceiling (or the light's hole in it).
        for (p, b) in points.iter().zip(&buried) {
            let up = scene
                .closest_drawn(&Ray::new(p.position, Vec3::Y), &[])
                .unwrap();
            let to_ceiling = scene.bounds.max.y - p.position.y;
            assert_eq!(*b, up.t < 0.95 * to_ceiling, "{p:?}");
        }
    }
}
