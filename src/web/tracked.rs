//! A drawn value and whether its drawing is out of date, so that a page
//! draws only when something changed: the one way to change the value,
//! [`Tracked::edit`], marks it stale, and a binding cannot forget to.

/// `value` and whether what was drawn of it is stale.
#[derive(Debug)]
pub(super) struct Tracked<T> {
    value: T,
    stale: bool,
}

impl<T> Tracked<T> {
    /// A value not drawn yet (stale).
    pub(super) fn new(value: T) -> Self {
        Self { value, stale: true }
    }

    /// The value, to read or to draw.
    pub(super) fn get(&self) -> &T {
        &self.value
    }

    /// The value, to change: its drawing is stale from now on.
    pub(super) fn edit(&mut self) -> &mut T {
        self.stale = true;
        &mut self.value
    }

    /// The value, to change without marking it stale: only for a change
    /// whose caller decides itself whether to draw (the clock's tick).
    pub(super) fn edit_untracked(&mut self) -> &mut T {
        &mut self.value
    }

    /// Whether the drawing is stale; clears the mark (the caller draws).
    pub(super) fn take_stale(&mut self) -> bool {
        std::mem::replace(&mut self.stale, false)
    }
}
