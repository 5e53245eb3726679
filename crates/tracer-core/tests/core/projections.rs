//! The camera's projections against their definitions, never against each other: where a
//! known direction lands on a fisheye, the solid angles its pixels see (spherical triangles
//! from the rays' corner directions, summed), a closed furnace read through every projection in
//! every integrator, and the orthographic view of a plane under a point light against
//! E = I cos θ / R².

use crate::gi_support::*;
use glam::{DVec3, Vec3};
use std::f64::consts::PI;
use tracer_core::integrator::IntegratorKind;
use tracer_core::render::{Film, RenderSettings, render};
use tracer_core::scene::{Camera, Handedness, Light, Projection};

/// A camera at the origin looking along -Z, +Y up, +X right (right-handed).
fn looking_down_minus_z(projection: Projection, fov_deg: f32) -> Camera {
    Camera {
        position: [0.0; 3],
        look_at: [0.0, 0.0, -1.0],
        up: [0.0, 1.0, 0.0],
        fov_deg,
        projection,
        width: None,
    }
}

/// A point in direction (θ from the view axis, φ from +X towards +Y), 5 units away.
fn at(theta: f64, phi: f64) -> Vec3 {
    let d = DVec3::new(
        theta.sin() * phi.cos(),
        theta.sin() * phi.sin(),
        -theta.cos(),
    );
    (d * 5.0).as_vec3()
}

#[test]
fn a_known_direction_lands_at_the_radius_of_its_law() {
    let (w, h) = (401u32, 301u32);
    let radius = 0.5 * f64::from(w.min(h));
    let (cx, cy) = (0.5 * f64::from(w), 0.5 * f64::from(h));
    type Law = fn(f64, f64) -> f64;
    let laws: [(Projection, Law); 3] = [
        (Projection::FisheyeEquidistant, |t, tm| t / tm),
        (Projection::FisheyeEquisolid, |t, tm| {
            (t / 2.0).sin() / (tm / 2.0).sin()
        }),
        (Projection::Hemispherical, |t, tm| t.sin() / tm.sin()),
    ];
    for (projection, law) in laws {
        for fov in [180.0f32, 150.0, 60.0] {
            let basis = looking_down_minus_z(projection, fov).basis(Handedness::Right, w, h);
            let theta_max = f64::from(fov).to_radians() / 2.0;
            for k in 0..=8 {
                let theta = theta_max * f64::from(k) / 8.0 * 0.999;
                for phi in [0.0, 0.7, 2.0, 3.5, 5.9] {
                    let (x, y) = basis.project(at(theta, phi)).unwrap();
                    let r = law(theta, theta_max) * radius;
                    let (ex, ey) = (cx + r * phi.cos(), cy - r * phi.sin());
                    let off = (f64::from(x) - ex).hypot(f64::from(y) - ey);
                    assert!(
                        off < 0.5,
                        "{projection} fov {fov}: θ {theta:.3} φ {phi}: ({x}, {y}) vs ({ex:.2}, {ey:.2})"
                    );
                    // And the ray through that film position points back at the point.
                    let ray = basis.ray(x, y).unwrap();
                    let want = at(theta, phi).normalize();
                    assert!(ray.dir.angle_between(want) < 1e-3, "{projection} ray back");
                }
            }
            // Beyond the field: not on the film.
            if fov < 180.0 {
                assert!(basis.project(at(theta_max + 0.05, 1.0)).is_none());
            }
        }
    }
    // Equirectangular: azimuth across, elevation down, the view direction at the centre.
    let basis =
        looking_down_minus_z(Projection::Equirectangular, 0.0).basis(Handedness::Right, 400, 200);
    for (dir, want) in [
        (Vec3::NEG_Z, (200.0, 100.0)),
        (Vec3::X, (300.0, 100.0)),
        (Vec3::NEG_X, (100.0, 100.0)),
        (Vec3::new(0.0, 1.0, -1.0), (200.0, 50.0)),
        (Vec3::new(1.0, -1.0, 0.0), (300.0, 150.0)),
    ] {
        let (x, y) = basis.project(dir).unwrap();
        assert!(
            (x - want.0).abs() < 0.5 && (y - want.1).abs() < 0.5,
            "{dir}: ({x}, {y})"
        );
    }
}

/// Solid angle of the spherical triangle of unit vectors a, b, c (Van Oosterom & Strackee).
fn triangle_sr(a: DVec3, b: DVec3, c: DVec3) -> f64 {
    let num = a.dot(b.cross(c)).abs();
    let den = 1.0 + a.dot(b) + b.dot(c) + c.dot(a);
    2.0 * num.atan2(den)
}

/// The sum over the film of each `k` x `k` sub-pixel's solid angle, from the directions of
/// the rays through its corners; a corner outside the image circle is moved onto it (the
/// circle's edge sees θmax). Also the sum of each sub-pixel's solid angle times the cosine
/// of its centre ray with the view direction (the projected solid angle).
fn film_solid_angle(camera: &Camera, w: u32, h: u32, k: u32) -> (f64, f64) {
    let basis = camera.basis(Handedness::Right, w, h);
    let (cx, cy) = (0.5 * w as f32, 0.5 * h as f32);
    let radius = 0.5 * w.min(h) as f32;
    let dir = |x: f32, y: f32| -> DVec3 {
        let (mut x, mut y) = (x, y);
        if camera.projection.is_fisheye() {
            let (dx, dy) = (x - cx, y - cy);
            let r = dx.hypot(dy);
            if r > radius {
                x = cx + dx * radius / r * (1.0 - 1e-6);
                y = cy + dy * radius / r * (1.0 - 1e-6);
            }
        }
        basis.ray(x, y).unwrap().dir.as_dvec3()
    };
    let step = 1.0 / k as f32;
    let (mut total, mut projected) = (0.0, 0.0);
    for j in 0..h * k {
        for i in 0..w * k {
            let (x0, y0) = (i as f32 * step, j as f32 * step);
            let (x1, y1) = (x0 + step, y0 + step);
            let (xm, ym) = (x0 + 0.5 * step, y0 + 0.5 * step);
            if camera.projection.is_fisheye() {
                // Sub-pixels wholly outside the circle see nothing.
                let near = |lo: f32, hi: f32, c: f32| c.clamp(lo, hi) - c;
                if near(x0, x1, cx).hypot(near(y0, y1, cy)) > radius {
                    continue;
                }
            }
            let (a, b, c, d) = (dir(x0, y0), dir(x1, y0), dir(x1, y1), dir(x0, y1));
            let sr = triangle_sr(a, b, c) + triangle_sr(a, c, d);
            total += sr;
            projected += sr * dir(xm, ym).dot(DVec3::NEG_Z).max(0.0);
        }
    }
    (total, projected)
}

#[test]
fn fisheye_pixels_see_the_field_of_views_solid_angle() {
    for projection in [
        Projection::FisheyeEquidistant,
        Projection::FisheyeEquisolid,
        Projection::Hemispherical,
    ] {
        for fov in [180.0f32, 120.0] {
            let camera = looking_down_minus_z(projection, fov);
            let (total, projected) = film_solid_angle(&camera, 120, 100, 3);
            let theta_max = f64::from(fov).to_radians() / 2.0;
            let cap = 2.0 * PI * (1.0 - theta_max.cos());
            let cap_projected = PI * theta_max.sin().powi(2);
            println!(
                "{projection} {fov}°: Σ Ω = {total:.5} sr (exact {cap:.5}), Σ Ω cos θ = \
                 {projected:.5} (exact {cap_projected:.5})"
            );
            // The hemispherical law packs the horizon into the circle's last sliver, where the
            // corners' chord polygon falls short; its projected solid angle is well behaved.
            let tol = if projection == Projection::Hemispherical && fov == 180.0 {
                0.02
            } else {
                0.002
            };
            assert!(
                (total / cap - 1.0).abs() < tol,
                "{projection} {fov}: {total} vs {cap}"
            );
            assert!(
                (projected / cap_projected - 1.0).abs() < 0.003,
                "{projection} {fov}: {projected} vs {cap_projected}"
            );
        }
    }
    let camera = looking_down_minus_z(Projection::Equirectangular, 0.0);
    let (total, _) = film_solid_angle(&camera, 96, 48, 2);
    assert!(
        (total / (4.0 * PI) - 1.0).abs() < 0.002,
        "equirectangular: {total}"
    );
}

/// Each projection's density of directions over the film is its film area per solid angle:
/// checked against the solid angle of small film squares.
#[test]
fn direction_density_is_the_film_area_per_solid_angle() {
    let (w, h) = (200u32, 160u32);
    for projection in [
        Projection::Perspective,
        Projection::FisheyeEquidistant,
        Projection::FisheyeEquisolid,
        Projection::Hemispherical,
        Projection::Equirectangular,
    ] {
        let basis = looking_down_minus_z(projection, 150.0).basis(Handedness::Right, w, h);
        for (x, y) in [
            (100.0f32, 80.0f32),
            (30.5, 77.0),
            (140.0, 20.0),
            (111.0, 151.0),
        ] {
            let Some(centre) = basis.ray(x, y) else {
                continue;
            };
            let e = 0.05;
            let d = |dx: f32, dy: f32| basis.ray(x + dx, y + dy).unwrap().dir.as_dvec3();
            let (a, b, c, q) = (d(-e, -e), d(e, -e), d(e, e), d(-e, e));
            let sr = triangle_sr(a, b, c) + triangle_sr(a, c, q);
            let film_share = f64::from(2.0 * e).powi(2) / f64::from(w * h);
            let want = film_share / sr;
            let got = f64::from(basis.direction_density(centre.dir));
            assert!(
                (got / want - 1.0).abs() < 2e-3,
                "{projection} at ({x}, {y}): {got} vs {want}"
            );
        }
    }
}

/// The closed box [0, 2]³, every face emitting 100 cd/m² and reflecting diffusely with `rho`.
fn furnace(camera: Camera, rho: f32) -> (tracer_core::scene::Scene, tracer_core::scene::Setup) {
    let sc = box_scene(2.0, 2.0, 2.0, vec![]);
    let st = setup(&sc, camera, vec![], vec![emitting(diffuse(rho), 100.0); 6]);
    (sc, st)
}

/// Pixels wholly inside the image (all of them but a fisheye's circle edge and corners).
fn inside(camera: &Camera, w: u32, h: u32, x: u32, y: u32) -> bool {
    let basis = camera.basis(Handedness::Right, w, h);
    [(0, 0), (1, 0), (0, 1), (1, 1)]
        .iter()
        .all(|&(i, j)| basis.ray((x + i) as f32, (y + j) as f32).is_some())
}

/// Every pixel inside the image within 4.5 of its standard errors of `exact` and their mean
/// within 1 %; pixels wholly outside are black.
fn reads_uniformly(film: &Film, camera: &Camera, exact: f64, skip_rows: u32, what: &str) {
    let (w, h) = (film.width, film.height);
    let basis = camera.basis(Handedness::Right, w, h);
    let (mut sum, mut var, mut n) = (0.0, 0.0, 0);
    for y in 0..h {
        for x in 0..w {
            let i = film.index(x, y);
            let l = film.mean_luminance(i);
            if basis.pixel_outside(x, y) {
                assert_eq!(
                    l, 0.0,
                    "{what}: pixel ({x}, {y}) outside the circle is black"
                );
                continue;
            }
            if !inside(camera, w, h, x, y) || y < skip_rows || y >= h - skip_rows {
                continue;
            }
            let se = film.luminance_std_error(i).unwrap_or(f64::INFINITY);
            assert!(
                (l - exact).abs() < 4.5 * se.max(1e-3 * exact),
                "{what}: pixel ({x}, {y}) reads {l} ± {se}, exact {exact}"
            );
            sum += l;
            var += se * se;
            n += 1;
        }
    }
    let mean = sum / f64::from(n);
    let se = var.sqrt() / f64::from(n);
    println!("{what}: {n} pixels inside, mean {mean:.3} ± {se:.3} (exact {exact})");
    assert!(
        (mean / exact - 1.0).abs() < 0.01,
        "{what}: mean {mean} vs {exact}"
    );
}

#[test]
fn a_furnace_reads_the_same_through_every_projection_in_every_integrator() {
    let (w, h) = (20u32, 16u32);
    for projection in Projection::ALL {
        let mut camera = Camera {
            position: [1.0, 1.0, 1.0],
            look_at: [0.7, 1.1, 0.0],
            up: [0.0, 1.0, 0.0],
            fov_deg: if projection.is_fisheye() {
                180.0
            } else {
                100.0
            },
            projection,
            width: Some(1.5),
        };
        if projection == Projection::Orthographic {
            camera.position = [1.0, 1.0, 1.5];
        }
        for integrator in IntegratorKind::ALL {
            if integrator.check_projection(projection).is_err() {
                assert_eq!(
                    (integrator, projection),
                    (IntegratorKind::Light, Projection::Orthographic)
                );
                continue;
            }
            // Direct light samples an enclosure's walls as area lights, a heavy-tailed
            // estimate near the corners: it looks at black emitters (ρ = 0), which read Le
            // exactly; the others at L = Le / (1 − ρ), ρ = 0.5.
            let (rho, exact, spp) = match integrator {
                IntegratorKind::Direct => (0.0, 100.0, 4),
                _ => (0.5, 200.0, 96),
            };
            let (sc, st) = furnace(camera, rho);
            let settings = RenderSettings {
                width: w,
                height: h,
                samples_per_pixel: spp,
                integrator,
                ..RenderSettings::default()
            };
            let (film, _) = render(&sc, &st, &settings);
            // Light tracing a panorama has infinite variance at its poles, where a pixel's
            // importance grows as 1 / cos(elevation) (∫ W² dω diverges, if only as a
            // logarithm): its top and bottom rows are left out (the mean keeps the rest).
            let poles = u32::from(
                integrator == IntegratorKind::Light && projection == Projection::Equirectangular,
            );
            let what = format!("{projection}, {integrator}");
            reads_uniformly(&film, &camera, exact, poles, &what);
        }
    }
}

/// An orthographic camera looking straight down at a diffuse floor lit by a point light: each
/// pixel sees the floor point under it, whose luminance is ρ E / π with E = I cos θ / R² (no
/// perspective: pixel columns are equally spaced on the floor).
#[test]
fn orthographic_view_of_a_plane_shows_its_illuminance_pattern() {
    let sc = box_scene(4.0, 2.0, 4.0, vec![]);
    let rho = 0.6f32;
    let mut mats = vec![diffuse(0.0); 6];
    mats[0] = diffuse(rho);
    let (w, h) = (64u32, 16u32);
    let camera = Camera {
        position: [2.0, 1.5, 2.0],
        look_at: [2.0, 0.0, 2.0],
        up: [0.0, 0.0, -1.0],
        fov_deg: 45.0,
        projection: Projection::Orthographic,
        width: Some(3.2),
    };
    let light_at = Vec3::new(1.3, 1.0, 2.0);
    let intensity = 200.0f32;
    let light = Light::point(light_at.to_array(), intensity);
    let st = setup(&sc, camera, vec![light], mats);
    // (The walls are black: no light comes back.)
    for integrator in [
        IntegratorKind::Direct,
        IntegratorKind::Path,
        IntegratorKind::Bidirectional,
    ] {
        let settings = RenderSettings {
            width: w,
            height: h,
            // Sample 0 goes through the pixel's centre, whose floor point is known exactly.
            samples_per_pixel: 1,
            integrator,
            ..RenderSettings::default()
        };
        let (film, _) = render(&sc, &st, &settings);
        let y = h / 2;
        let mut worst = 0.0f64;
        for x in 0..w {
            // The floor point under the pixel's centre: x across from 2 − 1.6 to 2 + 1.6
            // (right = forward × up = (0, -1, 0) × (0, 0, -1) = +X), z from 2 − 0.4 to 2 + 0.4
            // down the image (up is -Z; the height is the width over the aspect ratio, 4).
            let px = 2.0 - 1.6 + 3.2 * (f64::from(x) + 0.5) / f64::from(w);
            let pz = 2.0 - 0.4 + 0.8 * (f64::from(y) + 0.5) / f64::from(h);
            let d = DVec3::new(px, 0.0, pz) - light_at.as_dvec3();
            let r2 = d.length_squared();
            let e = f64::from(intensity) * (-d.y) / r2.sqrt() / r2;
            let exact = f64::from(rho) * e / PI;
            let l = film.mean_luminance(film.index(x, y));
            let rel = (l / exact - 1.0).abs();
            worst = worst.max(rel);
            assert!(
                rel < 1e-3,
                "{integrator}: pixel {x} at x = {px:.3} reads {l}, exact {exact} (E = I cos θ / R²)"
            );
        }
        println!("orthographic floor, {integrator}: worst {worst:.4} along row {y}");
    }
}

/// What evalglare does with a fisheye image: the illuminance at the eye from the luminances it
/// sees, E = Σ L cos θ ω. A dark room (ρ = 0) whose ceiling glows at Le, seen from a tilted
/// eye: E = Le π F, F the form factor of the ceiling from the eye (Lambert's contour formula).
/// The hemispherical film's area is in proportion to the projected solid angle, so there
/// E = π × the mean luminance over the image circle = Σ L / R² (pixels); the equidistant
/// fisheye weighs each pixel by its solid angle (from the direction density checked above)
/// and its cosine.
#[test]
fn a_fisheye_image_gives_the_illuminance_at_the_eye() {
    let sc = box_scene(4.0, 3.0, 4.0, vec![]);
    let le = 100.0f32;
    let mut mats = vec![diffuse(0.0); 6];
    mats[1] = emitting(diffuse(0.0), le);
    let eye = Vec3::new(1.5, 1.2, 2.2);
    let n = Vec3::new(0.3, 1.0, -0.2).normalize();
    let ceiling = box_faces(4.0, 3.0, 4.0)[1].1.map(DVec3::from_array);
    let exact = f64::from(le) * PI * form_factor(eye.as_dvec3(), n.as_dvec3(), &ceiling);
    let (w, h) = (240u32, 240u32);
    for projection in [Projection::Hemispherical, Projection::FisheyeEquidistant] {
        let camera = Camera {
            position: eye.to_array(),
            look_at: (eye + n).to_array(),
            up: [1.0, 0.0, 0.0],
            fov_deg: 180.0,
            projection,
            width: None,
        };
        let st = setup(&sc, camera, vec![], mats.clone());
        let settings = RenderSettings {
            width: w,
            height: h,
            samples_per_pixel: 16,
            integrator: IntegratorKind::Direct,
            ..RenderSettings::default()
        };
        let (film, _) = render(&sc, &st, &settings);
        let basis = camera.basis(Handedness::Right, w, h);
        let radius = 0.5 * f64::from(w.min(h));
        let mut e = 0.0;
        for y in 0..h {
            for x in 0..w {
                let l = film.mean_luminance(film.index(x, y));
                if projection == Projection::Hemispherical {
                    e += l / (radius * radius);
                } else if let Some(ray) = basis.ray(x as f32 + 0.5, y as f32 + 0.5) {
                    let sr = 1.0 / (f64::from(basis.direction_density(ray.dir)) * f64::from(w * h));
                    e += l * f64::from(ray.dir.dot(n).max(0.0)) * sr;
                }
            }
        }
        println!("{projection}: E from the image {e:.4} lx, exact Le π F = {exact:.4} lx");
        assert!(
            (e / exact - 1.0).abs() < 0.005,
            "{projection}: {e} vs {exact}"
        );
    }
}
