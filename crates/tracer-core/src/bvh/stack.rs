//! The traversal stack: a fixed buffer that is not cleared before use (a ray touches only the
//! few entries it pushes; zeroing the whole buffer cost more than some traversals).

use std::mem::MaybeUninit;

/// A stack over borrowed, possibly uninitialised storage. Entries below `len` are initialised:
/// `push` writes before it counts, `pop` and `top_mut` read only below `len`.
pub(crate) struct Stack<'a, T: Copy> {
    items: &'a mut [MaybeUninit<T>],
    len: usize,
}

impl<'a, T: Copy> Stack<'a, T> {
    #[inline(always)]
    pub fn new(items: &'a mut [MaybeUninit<T>]) -> Self {
        Self { items, len: 0 }
    }

    /// Pushes `x`; panics when the storage is full (its size bounds the tree depth).
    #[inline(always)]
    pub fn push(&mut self, x: T) {
        self.items[self.len].write(x);
        self.len += 1;
    }

    #[inline(always)]
    pub fn pop(&mut self) -> Option<T> {
        self.len = self.len.checked_sub(1)?;
        // SAFETY: the entry at the old `len - 1` was written by `push` (see the type's docs).
        Some(unsafe { self.items[self.len].assume_init() })
    }

    /// The last `n` entries pushed (`n <= len`), bottom first.
    #[inline(always)]
    pub fn top_mut(&mut self, n: usize) -> &mut [T] {
        let top = &mut self.items[self.len - n..self.len];
        // SAFETY: entries below `len` are initialised, and `MaybeUninit<T>` has the size,
        // alignment and layout of `T`, so a slice of initialised ones is a slice of `T`.
        unsafe { &mut *(std::ptr::from_mut(top) as *mut [T]) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pushes_pops_and_sorts_the_top() {
        let mut buf = [MaybeUninit::uninit(); 4];
        let mut s = Stack::new(&mut buf);
        assert_eq!(s.pop(), None);
        for x in [5, 3, 1] {
            s.push(x);
        }
        s.top_mut(2).sort_unstable();
        assert_eq!(s.top_mut(3), &[5, 1, 3][..]);
        assert_eq!(
            (s.pop(), s.pop(), s.pop(), s.pop()),
            (Some(3), Some(1), Some(5), None)
        );
    }
}
