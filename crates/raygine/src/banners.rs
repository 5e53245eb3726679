//! The status and error banners over the picture: each has a dismiss button, and each expires
//! (notices after a few seconds, errors after longer) so stale messages do not pile up.

use egui::{Color32, RichText};
use std::time::{Duration, Instant};

/// Which banner.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BannerKind {
    Error,
    Notice,
}

/// When each banner's current text appeared.
#[derive(Debug)]
pub struct Banners {
    /// How long a notice stays.
    pub notice_ttl: Duration,
    /// How long an error stays.
    pub error_ttl: Duration,
    error: Option<(String, Instant)>,
    notice: Option<(String, Instant)>,
}

impl Default for Banners {
    fn default() -> Self {
        Self {
            notice_ttl: Duration::from_secs(8),
            error_ttl: Duration::from_secs(30),
            error: None,
            notice: None,
        }
    }
}

impl Banners {
    /// Notes new texts and clears the banners whose time is up. Returns how long until the next
    /// one expires, so the UI can wake up for it.
    pub fn expire(
        &mut self,
        error: &mut Option<String>,
        notice: &mut Option<String>,
        now: Instant,
    ) -> Option<Duration> {
        let a = expire_one(&mut self.error, error, self.error_ttl, now);
        let b = expire_one(&mut self.notice, notice, self.notice_ttl, now);
        match (a, b) {
            (Some(a), Some(b)) => Some(a.min(b)),
            (a, b) => a.or(b),
        }
    }
}

fn expire_one(
    seen: &mut Option<(String, Instant)>,
    text: &mut Option<String>,
    ttl: Duration,
    now: Instant,
) -> Option<Duration> {
    let Some(t) = text.as_deref() else {
        *seen = None;
        return None;
    };
    let since = match seen {
        Some((s, since)) if s == t => *since,
        _ => {
            *seen = Some((t.to_owned(), now));
            now
        }
    };
    let age = now.saturating_duration_since(since);
    if age >= ttl {
        *text = None;
        *seen = None;
        None
    } else {
        Some(ttl - age)
    }
}

/// Draws the banners stacked from the top of `ui`; returns the one the user dismissed.
pub fn banners_ui(
    ui: &mut egui::Ui,
    error: Option<&str>,
    notice: Option<&str>,
) -> Option<BannerKind> {
    let mut dismissed = None;
    for (kind, text, colour, name) in [
        (
            BannerKind::Error,
            error.map(|e| format!("Error: {e}")),
            Color32::from_rgb(255, 120, 110),
            "Dismiss error",
        ),
        (
            BannerKind::Notice,
            notice.map(str::to_owned),
            Color32::LIGHT_GREEN,
            "Dismiss notice",
        ),
    ] {
        let Some(text) = text else {
            continue;
        };
        egui::Frame::NONE
            .fill(Color32::from_black_alpha(200))
            .corner_radius(4.0)
            .inner_margin(egui::Margin::symmetric(6, 4))
            .show(ui, |ui| {
                ui.horizontal_top(|ui| {
                    let button = ui.small_button("×").on_hover_text("Dismiss");
                    button.widget_info(|| {
                        egui::WidgetInfo::labeled(egui::accesskit::Role::Button, true, name)
                    });
                    if button.clicked() {
                        dismissed = Some(kind);
                    }
                    ui.add(egui::Label::new(RichText::new(text).color(colour)).wrap());
                });
            });
        ui.add_space(4.0);
    }
    dismissed
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_notice_expires_and_a_new_text_restarts_its_clock() {
        let mut b = Banners::default();
        let t0 = Instant::now();
        let mut error = None;
        let mut notice = Some("saved".to_owned());
        assert_eq!(b.expire(&mut error, &mut notice, t0), Some(b.notice_ttl));
        let later = t0 + b.notice_ttl / 2;
        notice = Some("exported".to_owned());
        b.expire(&mut error, &mut notice, later);
        b.expire(&mut error, &mut notice, t0 + b.notice_ttl);
        assert_eq!(
            notice.as_deref(),
            Some("exported"),
            "the new text expired early"
        );
        assert_eq!(
            b.expire(&mut error, &mut notice, later + b.notice_ttl),
            None
        );
        assert_eq!(notice, None);
    }

    #[test]
    fn errors_stay_longer_than_notices() {
        let mut b = Banners::default();
        let t0 = Instant::now();
        let mut error = Some("bad file".to_owned());
        let mut notice = Some("saved".to_owned());
        b.expire(&mut error, &mut notice, t0);
        b.expire(&mut error, &mut notice, t0 + b.notice_ttl);
        assert_eq!(notice, None);
        assert!(error.is_some());
        b.expire(&mut error, &mut notice, t0 + b.error_ttl);
        assert_eq!(error, None);
    }
}
