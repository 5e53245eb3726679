//! The viewer's tests through egui_kittest, built as one test binary (the GUI stack is linked
//! once): `viewer` (widgets, files, rendering), `commands` (the command path), `denoise` and
//! `first_view` (previews, status figures and exposure in a scene's first seconds).

mod commands;
mod denoise;
mod first_view;
mod viewer;
