//! The pixels' illuminance measured on demand: a session that does not measure it starts when
//! asked, between passes and without a restart, and its sums then equal a one-shot render's of
//! the same samples, bit for bit.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::sync::Arc;
use std::time::Duration;
use tracer_core::integrator::IntegratorKind;
use tracer_core::render::{
    ILLUMINANCE_SAMPLES, RenderSession, RenderSettings, Snapshot, render, render_samples,
};
use tracer_core::scene::builtin_cornell_box;

const WAIT: Duration = Duration::from_secs(60);

#[test]
fn a_finished_render_measures_the_illuminance_when_asked_without_a_restart() {
    let loaded = builtin_cornell_box(None).unwrap();
    let scene = Arc::new(builtin_cornell_box(None).unwrap().scene);
    for integrator in [IntegratorKind::Path, IntegratorKind::Bidirectional] {
        let settings = RenderSettings {
            width: 48,
            height: 32,
            samples_per_pixel: 3,
            integrator,
            pixel_illuminance: false,
            ..RenderSettings::default()
        };
        let session = RenderSession::new(2, Arc::new(|| {})).unwrap();
        let generation = session.start(Snapshot {
            scene: Arc::clone(&scene),
            setup: loaded.setup.clone(),
            settings,
            time_limit: None,
            adaptive: false,
        });
        assert!(session.wait_for(WAIT, |st| st.generation == generation && st.finished));
        let before = session.with_film(|f| f.unwrap().accum.clone());
        assert!(before.pixels().all(|p| p.illuminance == 0), "{integrator}");
        assert!(session.with_film(|f| !f.unwrap().illuminance_measured(0)));
        let rays_before = session.stats().rays;

        session.measure_illuminance();
        let total = 3 + ILLUMINANCE_SAMPLES;
        assert!(session.wait_for(WAIT, |st| st.finished && st.samples_per_pixel == total));
        assert_eq!(session.generation(), generation, "no restart");
        assert!(session.stats().rays > rays_before, "the ray count goes on");
        let after = session.with_film(|f| {
            let f = f.unwrap();
            assert_eq!(f.generation, generation);
            assert!((0..f.accum.len()).all(|i| f.illuminance_measured(i)));
            f.accum.clone()
        });
        assert_eq!(after.illuminance_from, 3, "{integrator}");

        // Luminance: the same as rendering all the samples at once, with or without the
        // illuminance (it has streams of its own).
        let all = RenderSettings {
            samples_per_pixel: total,
            ..settings
        };
        let (oneshot, _) = render(&scene, &loaded.setup, &all);
        for (a, b) in after.pixels().zip(oneshot.pixels()) {
            assert_eq!((a.rgb, a.splat_rgb, a.count), (b.rgb, b.splat_rgb, b.count));
        }
        // Illuminance: exactly that of samples 3.. measured from the start.
        let measured = RenderSettings {
            pixel_illuminance: true,
            ..settings
        };
        let (later, _) = render_samples(&scene, &loaded.setup, &measured, 3..total);
        let mut lit = 0;
        for (i, (a, b)) in after.pixels().zip(later.pixels()).enumerate() {
            assert_eq!(a.illuminance, b.illuminance, "{integrator} pixel {i}");
            assert_eq!(after.mean_illuminance(i), later.mean_illuminance(i));
            lit += usize::from(b.illuminance > 0);
        }
        assert!(lit > after.len() / 2, "{integrator}: {lit} pixels lit");
    }
}

#[test]
fn asked_before_the_first_pass_it_is_measured_from_the_start() {
    let loaded = builtin_cornell_box(None).unwrap();
    let scene = Arc::new(builtin_cornell_box(None).unwrap().scene);
    let settings = RenderSettings {
        width: 32,
        height: 24,
        samples_per_pixel: 2,
        integrator: IntegratorKind::Bidirectional,
        pixel_illuminance: false,
        ..RenderSettings::default()
    };
    let session = RenderSession::new(1, Arc::new(|| {})).unwrap();
    session.measure_illuminance();
    let generation = session.start(Snapshot {
        scene: Arc::clone(&scene),
        setup: loaded.setup.clone(),
        settings,
        time_limit: None,
        adaptive: false,
    });
    assert!(session.wait_for(WAIT, |st| st.generation == generation && st.finished));
    assert_eq!(session.stats().samples_per_pixel, 2, "no extra samples");
    let film = session.with_film(|f| f.unwrap().accum.clone());
    assert_eq!(film.illuminance_from, 0);
    let measured = RenderSettings {
        pixel_illuminance: true,
        ..settings
    };
    let (oneshot, _) = render(&scene, &loaded.setup, &measured);
    assert_eq!(film, oneshot);
}
