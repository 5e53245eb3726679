//! What the user asked the viewer for. Panels, windows, the viewport and the keyboard shortcuts
//! return these values; the app's `apply` carries them out, in one place.
//!
//! Plain value edits (a light's position, a material's colour, the sky's luminance) go straight
//! into the document's setup, as egui widgets edit the value they are given; structural edits
//! (lights, luminaires, environment maps, visibility, grids) are [`Edit`] commands. The app turns each finished interaction into one
//! undo step either way. Everything else — files, history, the render, messages, the
//! selection — is a command too.

use crate::file_ops::DialogPurpose;
use crate::unsaved::Switch;
use std::path::PathBuf;

/// One thing the user asked for.
#[derive(Clone, Debug, PartialEq)]
pub enum Command {
    /// Open another scene or quit; asks first when that would drop unsaved edits.
    Switch(Switch),
    /// A structural edit of the setup.
    Edit(Edit),
    /// Open the path window for `purpose` (a typed path; Browse… runs the native dialog).
    PromptPath(DialogPurpose),
    /// Run the native file dialog for the path window, starting at `suggested`.
    Browse {
        purpose: DialogPurpose,
        suggested: PathBuf,
    },
    /// Carry out `purpose` with a path the user confirmed.
    RunPathAction(DialogPurpose, PathBuf),
    /// Save the scene settings beside the scene (the built-in scene asks where).
    SaveSidecar,
    Undo,
    Redo,
    /// Reset the camera to frame the scene (keeps the field of view).
    FrameScene,
    /// Return to the scene's own camera: as the scene (or its sidecar) gave it when opened, or
    /// as last saved.
    ResetCamera,
    /// Pause or resume rendering.
    TogglePause,
    /// Show or drop the ground plane under a lone object.
    SetGround(bool),
    /// Flip between the denoised and the raw picture (D).
    ToggleDenoise,
    /// Open the "Render image…" form for the current view.
    OpenRenderImageForm,
    /// Start the "Render image…" job with the form's values, writing `path`.
    StartRenderImage(PathBuf),
    CancelRenderImage,
    /// Stop waiting for the scene being loaded (the current scene stays).
    CancelLoad,
    /// Select a material slot (the surface clicked, or a name in the Materials panel).
    Select(Option<u32>),
    /// Write `text` to `path` in the background (the grid readings' CSV and JSON).
    WriteText {
        path: PathBuf,
        text: String,
    },
    /// Save the measurement report: the grids' CSV now, the viewport's picture as `png` when
    /// the window's screenshot arrives.
    SaveReport {
        png: PathBuf,
        csv: PathBuf,
        csv_text: String,
    },
    /// Show an error in the viewport's banner.
    Error(String),
    /// Show a notice in the viewport's banner.
    Notice(String),
    DismissError,
    DismissNotice,
}

/// A structural edit of the setup (see `app/edits.rs`); each finished one is an undo step.
#[derive(Clone, Debug, PartialEq)]
pub enum Edit {
    /// A point light where a scene without a sidecar gets its light, beside those there.
    AddLight,
    RemoveLight(usize),
    /// Read an IES or EULUMDAT file on a background job, then add it as a luminaire.
    AddLuminaire(PathBuf),
    /// Read a latitude-longitude `.hdr` or `.exr` map on a background job, then make it the
    /// environment (a map that cannot be read leaves the environment as it was).
    LoadEnvironmentMap(PathBuf),
    /// Hide or show these material slots.
    SetHidden {
        slots: Vec<u32>,
        hidden: bool,
    },
    ShowAll,
    /// A work plane fitted to the scene.
    AddWorkPlane,
    /// A grid over the plane of this material slot.
    AddGridOnSurface(u32),
    /// Grid `0` becomes the given grid (its points or corners edited).
    ReplaceGrid(usize, Box<tracer_core::measure::Grid>),
    RemoveGrid(usize),
}

/// Commands collected during a frame, applied once the panels have drawn.
pub type Commands = Vec<Command>;
