//! Undo and redo of scene edits (camera, lights, materials, visibility).
//!
//! The app edits its `Setup` freely; once an interaction ends (no pointer button held), the
//! edited setup is committed as one step, so a whole slider drag undoes at once.

use tracer_core::scene::Setup;

/// Steps kept; older ones are dropped.
const MAX_STEPS: usize = 200;

#[derive(Debug)]
pub struct History {
    committed: Setup,
    undo: Vec<Setup>,
    redo: Vec<Setup>,
}

impl History {
    pub fn new(setup: &Setup) -> Self {
        Self {
            committed: setup.clone(),
            undo: Vec::new(),
            redo: Vec::new(),
        }
    }

    /// Records `current` as a step if it differs from the last committed state.
    pub fn commit(&mut self, current: &Setup) {
        if *current != self.committed {
            let previous = std::mem::replace(&mut self.committed, current.clone());
            self.undo.push(previous);
            if self.undo.len() > MAX_STEPS {
                self.undo.remove(0);
            }
            self.redo.clear();
        }
    }

    /// The state before the last step (committing `current` first), if any.
    pub fn undo(&mut self, current: &Setup) -> Option<Setup> {
        self.commit(current);
        let previous = self.undo.pop()?;
        self.redo
            .push(std::mem::replace(&mut self.committed, previous.clone()));
        Some(previous)
    }

    pub fn redo(&mut self, current: &Setup) -> Option<Setup> {
        self.commit(current);
        let next = self.redo.pop()?;
        self.undo
            .push(std::mem::replace(&mut self.committed, next.clone()));
        Some(next)
    }

    pub fn can_undo(&self) -> bool {
        !self.undo.is_empty()
    }

    /// Whether undo would change anything from `current` (a committed step or pending edits).
    pub fn can_undo_from(&self, current: &Setup) -> bool {
        !self.undo.is_empty() || *current != self.committed
    }

    pub fn can_redo(&self) -> bool {
        !self.redo.is_empty()
    }

    /// Applies `change` to every state kept (a slot added to or dropped from the scene: each
    /// step's materials follow it).
    pub fn map(&mut self, change: impl Fn(&mut Setup)) {
        change(&mut self.committed);
        self.undo
            .iter_mut()
            .chain(self.redo.iter_mut())
            .for_each(change);
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    #[test]
    fn undo_redo_round_trip() {
        let loaded = tracer_core::scene::builtin_cornell_box(None).unwrap();
        let a = loaded.setup.clone();
        let mut h = History::new(&a);
        let mut b = a.clone();
        b.lights[0].position[0] = 1.0;
        h.commit(&b);
        let mut c = b.clone();
        c.camera.fov_deg = 20.0;
        assert_eq!(h.undo(&c), Some(b.clone()));
        assert_eq!(h.undo(&b), Some(a.clone()));
        assert_eq!(h.undo(&a), None);
        assert_eq!(h.redo(&a), Some(b.clone()));
        assert_eq!(h.redo(&b), Some(c.clone()));
        assert!(!h.can_redo());
    }
}
