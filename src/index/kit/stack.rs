//! The traversal stack of the tree indices: fixed capacity, on the call stack, not initialized
//! up front (zeroing an array of a few hundred entries would cost a memset per ray).

use std::mem::MaybeUninit;

/// A stack of at most `N` `Copy` items.
pub struct Stack<T: Copy, const N: usize> {
    items: [MaybeUninit<T>; N],
    len: usize,
}

impl<T: Copy, const N: usize> Stack<T, N> {
    #[inline(always)]
    pub fn new() -> Self {
        Stack {
            items: [const { MaybeUninit::uninit() }; N],
            len: 0,
        }
    }

    /// Pushes `item`. Callers bound their depth by `N`; an overflow panics on the bounds check.
    #[inline(always)]
    pub fn push(&mut self, item: T) {
        self.items[self.len].write(item);
        self.len += 1;
    }

    /// Writes `item` on top and keeps it only when `keep`: a push without a branch on `keep`
    /// (the slot above the top is written either way, so it must exist: callers bound their
    /// depth by `N - 1`).
    #[inline(always)]
    pub fn push_if(&mut self, item: T, keep: bool) {
        self.items[self.len].write(item);
        self.len += keep as usize;
    }

    /// Empties the stack.
    #[inline(always)]
    pub fn clear(&mut self) {
        self.len = 0;
    }

    #[inline(always)]
    pub fn pop(&mut self) -> Option<T> {
        self.len = self.len.checked_sub(1)?;
        // SAFETY: every slot below the old `len` was written by `push` and never moved out
        // (items are `Copy`).
        Some(unsafe { self.items[self.len].assume_init() })
    }
}

impl<T: Copy, const N: usize> Default for Stack<T, N> {
    fn default() -> Self {
        Self::new()
    }
}

#[cfg(test)]
mod tests {
    use super::Stack;

    #[test]
    fn last_in_first_out_and_empty_is_none() {
        let mut s = Stack::<u32, 3>::new();
        assert_eq!(s.pop(), None);
        s.push(1);
        s.push(2);
        s.push(3);
        assert_eq!((s.pop(), s.pop()), (Some(3), Some(2)));
        s.push(4);
        assert_eq!((s.pop(), s.pop(), s.pop()), (Some(4), Some(1), None));
    }

    #[test]
    fn push_if_keeps_only_when_asked() {
        let mut s = Stack::<u32, 3>::new();
        s.push_if(1, false);
        s.push_if(2, true);
        s.push_if(3, false);
        s.push_if(4, true);
        assert_eq!((s.pop(), s.pop(), s.pop()), (Some(4), Some(2), None));
    }

    #[test]
    #[should_panic]
    fn overflow_panics() {
        let mut s = Stack::<u8, 1>::new();
        s.push(1);
        s.push(2);
    }
}
