//! Radiance `.hdr` or OpenEXR bytes through `EnvironmentMap::from_bytes` (the content picks the
//! format); a map that loads becomes an environment light whose flux is finite and whose
//! sampled directions and densities are finite.
#![no_main]

use libfuzzer_sys::fuzz_target;
use std::path::Path;
use std::sync::Arc;
use tracer_core::light::{
    Environment, EnvironmentLight, EnvironmentMap, EnvironmentSource, LightSource,
};

fuzz_target!(|data: &[u8]| {
    if let Ok((map, _notes)) = EnvironmentMap::from_bytes(data, Path::new("fuzz.hdr")) {
        let env = Environment {
            source: EnvironmentSource::Map(Arc::new(map)),
            scale: 1.0,
            rotation_deg: 30.0,
            background: true,
        };
        let light = EnvironmentLight::new(&env, 1.0, Default::default(), 1.0, 1.0);
        let flux = light.power_lm();
        assert!(flux.is_finite() && flux >= 0.0, "flux {flux}");
        for u in [[0.0, 0.0], [0.5, 0.5], [0.999, 0.001], [0.3, 0.999]] {
            if let Some((w, pdf)) = light.sample_dir(u) {
                assert!(w.is_finite() && pdf.is_finite() && pdf > 0.0, "{w} {pdf}");
                let _ = light.radiance(w);
                let _ = light.dir_pdf(w);
            }
        }
    }
});
