//! The names of the integrators: on the command line, in the viewer and in files.

use crate::scene::Projection;

/// Which light transport to compute.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum IntegratorKind {
    /// Direct light and mirrors (the coursework's model).
    #[default]
    Direct,
    /// Global illumination (path tracing).
    Path,
    /// Global illumination (bidirectional path tracing).
    Bidirectional,
    /// Global illumination (light tracing).
    Light,
}

impl IntegratorKind {
    /// The global-illumination integrator the viewer opens in and `--gi` names by default.
    pub const DEFAULT_GI: IntegratorKind = IntegratorKind::Bidirectional;

    pub const ALL: [IntegratorKind; 4] = [
        IntegratorKind::Direct,
        IntegratorKind::Path,
        IntegratorKind::Bidirectional,
        IntegratorKind::Light,
    ];

    /// Whether this integrator can render through `projection`: the light tracer only splats,
    /// and the orthographic camera, whose importance is a delta in direction, takes no splat.
    pub fn check_projection(self, projection: Projection) -> Result<(), String> {
        if self == IntegratorKind::Light && projection == Projection::Orthographic {
            return Err(
                "the light tracer cannot render an orthographic camera: it only joins light \
                 paths to the eye, and no light path reaches an orthographic camera (all its \
                 rays are parallel); use --gi bdpt or path, or another projection"
                    .into(),
            );
        }
        Ok(())
    }

    /// Whether light subpaths are traced and splatted to the film.
    pub fn splats(self) -> bool {
        matches!(self, IntegratorKind::Bidirectional | IntegratorKind::Light)
    }

    /// The command line's name.
    pub fn name(self) -> &'static str {
        match self {
            IntegratorKind::Direct => "direct",
            IntegratorKind::Path => "path",
            IntegratorKind::Bidirectional => "bdpt",
            IntegratorKind::Light => "light",
        }
    }

    /// What the viewer shows.
    pub fn label(self) -> &'static str {
        match self {
            IntegratorKind::Direct => "Direct (coursework)",
            IntegratorKind::Path => "Global illumination (path)",
            IntegratorKind::Bidirectional => "Global illumination (bidirectional)",
            IntegratorKind::Light => "Global illumination (light tracing)",
        }
    }

    pub fn from_name(s: &str) -> Option<Self> {
        match s {
            "direct" => Some(IntegratorKind::Direct),
            "path" => Some(IntegratorKind::Path),
            "bdpt" | "bidirectional" => Some(IntegratorKind::Bidirectional),
            "light" | "ptracer" | "light-tracing" => Some(IntegratorKind::Light),
            "gi" => Some(IntegratorKind::DEFAULT_GI),
            _ => None,
        }
    }
}

impl std::fmt::Display for IntegratorKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}
