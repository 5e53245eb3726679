//! Keyboard shortcuts: what the user pressed this frame, read once before the panels draw.
//!
//! Typing never triggers a shortcut: while a text field (a path, a typed slider value) has
//! keyboard focus, plain keys (F, Home, P, D) and undo / redo belong to the field. Commands with Ctrl
//! (open, save, export, quit) still work, as they type nothing.

use crate::command::{Command, Commands};
use crate::file_ops::DialogPurpose;
use crate::unsaved::Switch;
use egui::{Key, KeyboardShortcut, Modifiers};

pub const SHORTCUT_OPEN: KeyboardShortcut = KeyboardShortcut::new(Modifiers::COMMAND, Key::O);
pub const SHORTCUT_SAVE: KeyboardShortcut = KeyboardShortcut::new(Modifiers::COMMAND, Key::S);
pub const SHORTCUT_EXPORT: KeyboardShortcut = KeyboardShortcut::new(Modifiers::COMMAND, Key::E);
pub const SHORTCUT_UNDO: KeyboardShortcut = KeyboardShortcut::new(Modifiers::COMMAND, Key::Z);
pub const SHORTCUT_QUIT: KeyboardShortcut = KeyboardShortcut::new(Modifiers::COMMAND, Key::Q);
pub const SHORTCUT_REDO: KeyboardShortcut =
    KeyboardShortcut::new(Modifiers::COMMAND.plus(Modifiers::SHIFT), Key::Z);
const SHORTCUT_REDO_Y: KeyboardShortcut = KeyboardShortcut::new(Modifiers::COMMAND, Key::Y);

/// The shortcuts pressed in one frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Pressed {
    pub open: bool,
    pub save: bool,
    pub export: bool,
    pub quit: bool,
    pub undo: bool,
    pub redo: bool,
    pub frame_scene: bool,
    pub reset_camera: bool,
    pub toggle_pause: bool,
    pub toggle_denoise: bool,
}

impl Pressed {
    /// Consumes this frame's shortcut keys. With a text field focused, only the Ctrl commands
    /// that type nothing are taken; every other key is left to the field.
    pub fn read(ctx: &egui::Context) -> Self {
        let typing = ctx.text_edit_focused();
        ctx.input_mut(|i| {
            // Redo first: Ctrl+Shift+Z also matches Ctrl+Z's modifiers loosely.
            let redo = !typing
                && (i.consume_shortcut(&SHORTCUT_REDO) || i.consume_shortcut(&SHORTCUT_REDO_Y));
            Self {
                open: i.consume_shortcut(&SHORTCUT_OPEN),
                save: i.consume_shortcut(&SHORTCUT_SAVE),
                export: i.consume_shortcut(&SHORTCUT_EXPORT),
                quit: i.consume_shortcut(&SHORTCUT_QUIT),
                undo: !typing && i.consume_shortcut(&SHORTCUT_UNDO),
                redo,
                frame_scene: !typing && i.consume_key(Modifiers::NONE, Key::F),
                reset_camera: !typing && i.consume_key(Modifiers::NONE, Key::Home),
                toggle_pause: !typing && i.consume_key(Modifiers::NONE, Key::P),
                toggle_denoise: !typing && i.consume_key(Modifiers::NONE, Key::D),
            }
        })
    }

    /// What the keys pressed ask for, in the order they act.
    pub fn commands(self) -> Commands {
        let mut out = Commands::new();
        if self.quit {
            out.push(Command::Switch(Switch::Quit));
        }
        if self.open {
            out.push(Command::PromptPath(DialogPurpose::Open));
        }
        if self.save {
            out.push(Command::SaveSidecar);
        }
        if self.export {
            out.push(Command::PromptPath(DialogPurpose::ExportPng));
        }
        if self.redo {
            out.push(Command::Redo);
        } else if self.undo {
            out.push(Command::Undo);
        }
        if self.frame_scene {
            out.push(Command::FrameScene);
        }
        if self.reset_camera {
            out.push(Command::ResetCamera);
        }
        if self.toggle_pause {
            out.push(Command::TogglePause);
        }
        if self.toggle_denoise {
            out.push(Command::ToggleDenoise);
        }
        out
    }
}
