//! Lights as the scene's setup sees them: the model types live in [`crate::light`].

pub use crate::light::{
    KindTag, LUMINANCE_WEIGHTS, Light, LightKind, LuminairePlacement, LuminousShape, ShapeChoice,
    Spot, luminance,
};
