//! Slots of a scratch array for the values a split program passes between its parts (the
//! Rust and C emitters' parts, `split`, and the JIT's): each value gets a slot no value still
//! to be read holds, the lowest free one, so the array stays as short as the values alive
//! across a part boundary at once.

use std::cmp::Reverse;
use std::collections::{BTreeSet, BinaryHeap};

/// Slots handed out to values in the order of the parts that write them, each slot free again
/// once the last part reading its value has run.
#[derive(Debug)]
pub struct ScratchSlots {
    free: BTreeSet<usize>,
    /// (last part reading the value in it, slot), the earliest freed first.
    busy: BinaryHeap<Reverse<(usize, usize)>>,
    count: usize,
}

impl ScratchSlots {
    /// No slot in use; new slots are numbered from `first` (the slots below are kept for
    /// something else, such as outputs).
    pub fn starting_at(first: usize) -> ScratchSlots {
        ScratchSlots {
            free: BTreeSet::new(),
            busy: BinaryHeap::new(),
            count: first,
        }
    }

    /// The slot of a value written in part `written` and last read in part `last_read`: the
    /// lowest slot whose value was last read before part `written`, else a new one. Values
    /// come in the order of the parts writing them.
    pub fn place(&mut self, written: usize, last_read: usize) -> usize {
        while let Some(&Reverse((read, slot))) = self.busy.peek() {
            if read >= written {
                break;
            }
            self.busy.pop();
            self.free.insert(slot);
        }
        let slot = self.free.pop_first().unwrap_or_else(|| {
            self.count += 1;
            self.count - 1
        });
        self.busy.push(Reverse((last_read, slot)));
        slot
    }

    /// The number of slots: those handed out and those below the first.
    pub fn count(&self) -> usize {
        self.count
    }
}

#[cfg(test)]
mod tests {
    use super::ScratchSlots;

    #[test]
    fn a_slot_is_reused_only_after_its_last_reader() {
        let mut slots = ScratchSlots::starting_at(2);
        assert_eq!(slots.place(0, 3), 2);
        assert_eq!(slots.place(1, 1), 3);
        assert_eq!(slots.place(2, 2), 3, "part 1 read slot 3's value last");
        assert_eq!(
            slots.place(3, 4),
            3,
            "slot 2's value is still read in part 3"
        );
        assert_eq!(slots.place(4, 5), 2);
        assert_eq!(slots.count(), 4);
    }
}
