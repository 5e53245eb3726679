//! UGR (CIE 117:1995) and DGP (Wienold & Christoffersen 2006) from a glare image and its
//! sources, each with a standard error.
//!
//! - Ev = Σ L cos θ ω over the image (the vertical illuminance at the eye).
//! - Lb = (Ev − the sources' share of it) / π: the indirect illuminance at the eye over π, i.e.
//!   the mean background luminance an eye adapts to. The image's sources' share is their pixels';
//!   the openings' (analytic sources), the light drawn into the image for them.
//! - UGR = 8 log₁₀(0.25 / Lb · Σ L² ω / p²).
//! - DGP = 5.87·10⁻⁵ Ev + 9.18·10⁻² log₁₀(1 + Σ L² ω / (Ev^1.87 p²)) + 0.16 (the paper's
//!   constants; evalglare 3.06 rounds them to 0.092 and 0.159, 0.001 lower), at most 1; with
//!   the low-light correction (evalglare's `-C l+`, for Ev < 1000 lx, only when asked) times
//!   e^(0.024 Ev − 4) / (1 + e^(0.024 Ev − 4)).
//!
//! The uncertainty: every figure is a smooth function of the pixels' mean luminances, which are
//! independent Monte Carlo estimates with known standard errors (an analytic source's luminance
//! is exact). Its standard error is the first-order (delta-method) one, √(Σ (∂F/∂Lⱼ)² σⱼ²), with
//! the derivatives worked out below. Where pixels share samples (bidirectional and light tracing
//! splat one light subpath into many), the same derivatives are applied to independent batches
//! of the samples instead, and the error is their spread ([`super::batches`]). Either way it
//! says how far the figure may move with more samples; it does not cover the image's resolution
//! or the choice of threshold.

use super::batches::SampleBatches;
use super::image::GlareImage;
use super::position_index::evalglare_index;
use super::source::GlareSource;
use std::f64::consts::{LN_10, PI};

/// evalglare applies its low-light correction below this vertical illuminance (lx).
pub const LOW_LIGHT_LX: f64 = 1000.0;

/// The figures of one way of finding the sources.
#[derive(Clone, Debug, PartialEq)]
pub struct GlareFigures {
    /// Vertical illuminance at the eye (lx) and its standard error.
    pub ev: f64,
    pub ev_se: f64,
    /// Background luminance (cd/m²) and its standard error.
    pub lb: f64,
    pub lb_se: f64,
    /// UGR, None without sources (or without background light); its standard error.
    pub ugr: Option<f64>,
    pub ugr_se: f64,
    /// UGR with evalglare's position indices (Levin's form above the line of sight) at the same
    /// sources: what evalglare would make of them.
    pub ugr_evalglare_index: Option<f64>,
    pub dgp: f64,
    pub dgp_se: f64,
    /// The independent batches the standard errors come from; None when they come from the
    /// pixels' own errors (taken as independent).
    pub error_batches: Option<usize>,
    /// Whether the low-light correction was asked for, and whether it changed DGP.
    pub low_light_asked: bool,
    pub low_light_applied: bool,
    pub sources: Vec<GlareSource>,
}

impl GlareFigures {
    /// Notes on where the figures leave their models' ranges.
    pub fn notes(&self) -> Vec<String> {
        let mut notes = Vec::new();
        let outside = self.sources.iter().filter(|s| s.outside_cie117()).count();
        if outside > 0 {
            notes.push(format!(
                "{outside} of {} sources lie outside CIE 117's 0.0003–0.1 sr (CIE 147:2002 \
                 treats small and large sources)",
                self.sources.len()
            ));
        }
        if self.ev <= 0.0 {
            notes.push("Ev is 0: the eye sees no light (is it inside a solid?)".to_owned());
        } else if self.lb <= 0.0 {
            notes.push("no background luminance: UGR is undefined".to_owned());
        }
        if self.ugr.is_some_and(|u| u > 30.0) {
            notes.push(
                "UGR above 30 lies beyond CIE 117's scale (10 to 30): read it as intolerable"
                    .to_owned(),
            );
        }
        if self.dgp >= 1.0 {
            notes.push("DGP is held at 1 (its formula gives more)".to_owned());
        }
        if !self.low_light_asked && self.ev < LOW_LIGHT_LX {
            notes.push(format!(
                "Ev {:.0} lx is below {LOW_LIGHT_LX:.0} lx: DGP is uncorrected \
                 (--dgp-low-light applies evalglare's low-light correction)",
                self.ev
            ));
        }
        notes
    }
}

/// The figures of `image` with `sources` (from the image, analytic, or both). With two or more
/// `batches` of the image's samples, the standard errors are their spread ([`super::batches`]:
/// for integrators whose samples splat into many pixels), else the per-pixel propagation.
pub fn glare_figures(
    image: &GlareImage,
    sources: Vec<GlareSource>,
    low_light: bool,
    batches: Option<&SampleBatches>,
) -> GlareFigures {
    let n = image.luminance.len();
    // Which image source each pixel belongs to.
    let mut owner: Vec<Option<usize>> = vec![None; n];
    for (k, s) in sources.iter().enumerate() {
        for &i in &s.pixels {
            owner[i] = Some(k);
        }
    }
    let cos_sr = |i: usize| image.direction[i].z.max(0.0) * image.solid_angle[i];
    let (ev, _) = image.illuminance();
    // Analytic sources (openings) are the light drawn into the image for them: the background
    // is the rest of those pixels (the same light, so Lb does not hang on how finely the image
    // resolves the opening against the exact integral).
    let analytic = sources.iter().any(|s| s.pixels.is_empty());
    let background_e: f64 = image
        .seen()
        .filter(|&i| owner[i].is_none())
        .map(|i| {
            let opening = if analytic {
                image.opening.get(i).copied().unwrap_or(0.0)
            } else {
                0.0
            };
            (image.luminance[i] - opening) * cos_sr(i)
        })
        .sum();
    let lb = (background_e / PI).max(0.0);
    let mut sources = sources;
    if let Some(b) = batches.filter(|b| b.len() >= 2) {
        // An image source's luminance is its pixels' ω-weighted mean: its error, too, is the
        // batches' spread.
        for s in sources.iter_mut().filter(|s| !s.pixels.is_empty()) {
            let omega: f64 = s.pixels.iter().map(|&i| image.solid_angle[i]).sum();
            if omega > 0.0 {
                let mut gradient = vec![0.0; n];
                for &i in &s.pixels {
                    gradient[i] = image.solid_angle[i] / omega;
                }
                s.luminance_se = b.std_error_of(&gradient).unwrap_or(f64::NAN);
            }
        }
    }
    let terms: Vec<f64> = sources
        .iter()
        .map(|s| s.luminance * s.luminance * s.solid_angle / (s.position_index * s.position_index))
        .collect();
    let sum: f64 = terms.iter().sum();
    let ugr = (sum > 0.0 && lb > 0.0).then(|| 8.0 * (0.25 * sum / lb).log10());
    let sum_evalglare: f64 = sources
        .iter()
        .map(|s| {
            let p = evalglare_index(s.direction).unwrap_or(s.position_index);
            s.luminance * s.luminance * s.solid_angle / (p * p)
        })
        .sum();
    let ugr_evalglare_index =
        (sum_evalglare > 0.0 && lb > 0.0).then(|| 8.0 * (0.25 * sum_evalglare / lb).log10());
    let ev_pow = ev.max(1e-12).powf(1.87);
    let g = sum / ev_pow;
    let raw_dgp = 5.87e-5 * ev + 9.18e-2 * (1.0 + g).log10() + 0.16;
    let (factor, dfactor) = if low_light && ev < LOW_LIGHT_LX {
        let e = (0.024 * ev - 4.0).exp();
        let f = e / (1.0 + e);
        (f, 0.024 * f * (1.0 - f))
    } else {
        (1.0, 0.0)
    };
    // DGP is a probability: evalglare holds it at 1.
    let capped = raw_dgp * factor > 1.0;
    let dgp = (raw_dgp * factor).min(1.0);

    // Derivatives with respect to each pixel's luminance, and the variances they carry; with
    // batches, the derivatives themselves (Ev, Lb, UGR, DGP), for the batches' spread.
    let batches = batches.filter(|b| b.len() >= 2);
    let mut gradients = batches.map(|_| [vec![0.0; n], vec![0.0; n], vec![0.0; n], vec![0.0; n]]);
    let (mut var_ev, mut var_lb, mut var_ugr, mut var_dgp) = (0.0, 0.0, 0.0, 0.0);
    for i in image.seen() {
        let d_ev = cos_sr(i);
        let (d_sum, d_lb) = match owner[i] {
            Some(k) => {
                let s = &sources[k];
                let p2 = s.position_index * s.position_index;
                (2.0 * s.luminance * image.solid_angle[i] / p2, 0.0)
            }
            None => (0.0, d_ev / PI),
        };
        let d_ugr = if ugr.is_some() {
            8.0 / LN_10 * (d_sum / sum - d_lb / lb)
        } else {
            0.0
        };
        let d_g = d_sum / ev_pow - 1.87 * g * d_ev / ev.max(1e-12);
        let d_raw = 5.87e-5 * d_ev + 9.18e-2 / LN_10 * d_g / (1.0 + g);
        let d_dgp = if capped {
            0.0
        } else {
            d_raw * factor + raw_dgp * dfactor * d_ev
        };
        if let Some(gr) = gradients.as_mut() {
            for (v, d) in gr.iter_mut().zip([d_ev, d_lb, d_ugr, d_dgp]) {
                v[i] = d;
            }
        }
        let se = image.std_error[i];
        if se != 0.0 {
            var_ev += (d_ev * se).powi(2);
            var_lb += (d_lb * se).powi(2);
            var_ugr += (d_ugr * se).powi(2);
            var_dgp += (d_dgp * se).powi(2);
        }
    }
    let [ev_se, lb_se, ugr_se, dgp_se] = match (batches, &gradients) {
        (Some(b), Some(gr)) => [0, 1, 2, 3].map(|k| b.std_error_of(&gr[k]).unwrap_or(f64::NAN)),
        _ => [var_ev, var_lb, var_ugr, var_dgp].map(f64::sqrt),
    };
    GlareFigures {
        ev,
        ev_se,
        lb,
        lb_se,
        ugr,
        ugr_se,
        ugr_evalglare_index,
        dgp,
        dgp_se,
        error_batches: batches.map(SampleBatches::len),
        low_light_asked: low_light,
        low_light_applied: factor < 1.0,
        sources,
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;
    use crate::glare::position_index::IndexRule;
    use glam::DVec3;

    /// A two-pixel "image": one source pixel straight ahead, one background pixel.
    fn two_pixels(l_src: f64, l_bg: f64, se: f64) -> GlareImage {
        GlareImage {
            width: 2,
            height: 1,
            luminance: vec![l_src, l_bg],
            std_error: vec![se, se],
            direction: vec![DVec3::Z, DVec3::new(0.6, 0.0, 0.8)],
            solid_angle: vec![0.01, 2.0],
            opening: vec![0.0; 2],
            basis: None,
        }
    }

    fn source_of(image: &GlareImage) -> GlareSource {
        GlareSource {
            label: "s".into(),
            direction: DVec3::Z,
            luminance: image.luminance[0],
            luminance_se: image.std_error[0],
            solid_angle: image.solid_angle[0],
            eye_illuminance: image.luminance[0] * image.solid_angle[0],
            position_index: 1.0,
            index_rule: IndexRule::GuthTable,
            pixels: vec![0],
        }
    }

    #[test]
    fn figures_follow_the_formulas() {
        let image = two_pixels(10_000.0, 50.0, 0.0);
        let f = glare_figures(&image, vec![source_of(&image)], false, None);
        let ev = 10_000.0 * 0.01 + 50.0 * 0.8 * 2.0;
        let lb = 50.0 * 0.8 * 2.0 / PI;
        assert!((f.ev - ev).abs() < 1e-9 && (f.lb - lb).abs() < 1e-9);
        let ugr = 8.0 * (0.25 / lb * 1e8 * 0.01).log10();
        assert!((f.ugr.unwrap() - ugr).abs() < 1e-9);
        let dgp = 5.87e-5 * ev + 0.0918 * (1.0 + 1e6 / ev.powf(1.87)).log10() + 0.16;
        assert!((f.dgp - dgp).abs() < 1e-12);
        assert_eq!((f.ugr_se, f.dgp_se), (0.0, 0.0));
        let low = glare_figures(&image, vec![source_of(&image)], true, None);
        let a = (0.024f64 * ev - 4.0).exp();
        assert!((low.dgp - dgp * a / (1.0 + a)).abs() < 1e-12 && low.low_light_applied);
    }

    /// The delta-method standard errors against finite differences of the figures.
    #[test]
    fn standard_errors_are_the_first_order_propagation() {
        let se = 30.0;
        let image = two_pixels(10_000.0, 50.0, se);
        let base = glare_figures(&image, vec![source_of(&image)], true, None);
        let mut var_ugr = 0.0;
        let mut var_dgp = 0.0;
        for i in 0..2 {
            let mut moved = image.clone();
            let h = 1e-3;
            moved.luminance[i] += h;
            let m = glare_figures(&moved, vec![source_of(&moved)], true, None);
            var_ugr += ((m.ugr.unwrap() - base.ugr.unwrap()) / h * se).powi(2);
            var_dgp += ((m.dgp - base.dgp) / h * se).powi(2);
        }
        assert!(
            (base.ugr_se / var_ugr.sqrt() - 1.0).abs() < 1e-4,
            "{base:?}"
        );
        assert!(
            (base.dgp_se / var_dgp.sqrt() - 1.0).abs() < 1e-4,
            "{base:?}"
        );
    }

    /// With batches, the error is the spread of the figures' linearisation over them: checked
    /// against finite differences of UGR and DGP applied to each batch.
    #[test]
    fn batch_errors_are_the_spread_of_the_linearised_figures() {
        let batches = SampleBatches {
            samples: vec![3, 3, 3, 3],
            luminance: vec![
                vec![9000.0, 52.0],
                vec![11_500.0, 47.0],
                vec![9800.0, 55.0],
                vec![9700.0, 46.0],
            ],
        };
        let mut image = two_pixels(0.0, 0.0, 1.0);
        for j in 0..2 {
            image.luminance[j] = batches
                .luminance
                .iter()
                .map(|l| f64::from(l[j]))
                .sum::<f64>()
                / 4.0;
        }
        let base = glare_figures(&image, vec![source_of(&image)], false, Some(&batches));
        assert_eq!(base.error_batches, Some(4));
        let h = 1e-3;
        let slopes: Vec<(f64, f64)> = (0..2)
            .map(|j| {
                let mut moved = image.clone();
                moved.luminance[j] += h;
                let m = glare_figures(&moved, vec![source_of(&moved)], false, None);
                (
                    (m.ugr.unwrap() - base.ugr.unwrap()) / h,
                    (m.dgp - base.dgp) / h,
                )
            })
            .collect();
        let spread = |pick: &dyn Fn(&(f64, f64)) -> f64| {
            let x: Vec<f64> = batches
                .luminance
                .iter()
                .map(|l| (0..2).map(|j| pick(&slopes[j]) * f64::from(l[j])).sum())
                .collect();
            let mean = x.iter().sum::<f64>() / 4.0;
            (x.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / 12.0).sqrt()
        };
        let (ugr_se, dgp_se) = (spread(&|s| s.0), spread(&|s| s.1));
        assert!(
            (base.ugr_se / ugr_se - 1.0).abs() < 1e-3,
            "{} vs {ugr_se}",
            base.ugr_se
        );
        assert!(
            (base.dgp_se / dgp_se - 1.0).abs() < 1e-3,
            "{} vs {dgp_se}",
            base.dgp_se
        );
        // One batch is no spread: the pixels' own errors are used.
        let one = SampleBatches {
            samples: vec![12],
            luminance: vec![vec![10_000.0, 50.0]],
        };
        let f = glare_figures(&image, vec![source_of(&image)], false, Some(&one));
        assert_eq!(f.error_batches, None);
    }
}
