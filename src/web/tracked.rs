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

    /// One frame's tick of the value's clock: `tick` changes the value
    /// without marking it, since it changes the drawing only while the
    /// clock runs, which `running` tells. Returns `tick`'s result and
    /// whether the frame must draw: a change since the last frame, or a
    /// clock that ran before or after the tick (so the frame it stops on
    /// draws too). Clears the mark (the caller draws).
    pub(super) fn tick<R>(
        &mut self,
        running: impl Fn(&T) -> bool,
        tick: impl FnOnce(&mut T) -> R,
    ) -> (R, bool) {
        let was_running = running(&self.value);
        let result = tick(&mut self.value);
        let stale = std::mem::replace(&mut self.stale, false);
        (result, stale || was_running || running(&self.value))
    }
}
