//! The viewer's tests through egui_kittest, built as one test binary (the GUI stack is linked
//! once): `viewer` (widgets, files, rendering) and `commands` (the command path).

mod commands;
mod denoise;
mod viewer;
