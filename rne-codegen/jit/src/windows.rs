//! Addresses within a one-byte displacement of a register: the lowering's loads and stores
//! of the stack and the constants' table, so that their machine code is short.
//!
//! x86-64 encodes an address's displacement in one byte when it lies in −128..=127 and in four
//! bytes otherwise. A derivative kernel's spill area and constants' table span kilobytes, and
//! Cranelift addresses a stack slot from `rsp` and a table from its one base register, so
//! about a third of the Panda arm's ∂ID instructions carried four-byte displacements: 9 bytes
//! for a spill's reload where 6 would do, in a kernel whose 52–59 KB of code exceed the 32 KB
//! instruction cache (docs/performance.md, "Short addresses"). The lowering therefore reads and
//! writes each such place through a *window*: a register holding the address 128 bytes into
//! a 256-byte stretch of the area, from which every place in the stretch is a one-byte
//! displacement away. At most [`WINDOWS`] are kept, the least recently used making room; one
//! costs two instructions (an address and an `and` with all ones: Cranelift folds a sum with a
//! constant, and a stack slot's address, into the displacement of the access, and an `and` it
//! does not see through). The addresses are the same, so the bits are too.

use cranelift_codegen::ir::Value;

/// The most windows held at once. Cranelift keeps each in a general-purpose register beside
/// the kernel's array pointers; on x86-64, of 8, 10, 12, 14 and 16, 12 was within 3 % of the
/// fastest on UR5's and the Panda arm's derivatives in lanes (with 16 Cranelift spilled and
/// reloaded the windows' registers, about 440 moves in the Panda arm's ∂ID; with 8 the
/// lowering remade windows about 480 times; docs/performance.md, "Short addresses"). AArch64
/// encodes a 12-bit scaled offset and needs none.
pub(crate) const WINDOWS: usize = if cfg!(target_arch = "x86_64") { 12 } else { 0 };

/// [`WINDOWS`], or as `RNE_JIT_WINDOWS` says (0 turns windows off; for measuring).
pub(crate) fn windows_limit() -> usize {
    std::env::var("RNE_JIT_WINDOWS")
        .ok()
        .and_then(|n| n.parse::<usize>().ok())
        .unwrap_or(WINDOWS)
}

/// Bytes a window spans: a one-byte displacement's range.
const SPAN: i32 = 256;

/// The window of the place `offset` bytes from an area's start: its number and the offset of
/// its register's address from the area's start (the middle of its span).
pub(crate) fn window_of(offset: i32) -> (i32, i32) {
    let number = offset.div_euclid(SPAN);
    (number, number * SPAN + SPAN / 2)
}

/// One window: the area's address it derives from, its number, its register and when it was
/// last used.
struct Window {
    area: Value,
    number: i32,
    register: Value,
    used: u64,
}

/// The windows held in one function.
pub(crate) struct Windows {
    limit: usize,
    held: Vec<Window>,
    clock: u64,
}

impl Windows {
    pub(crate) fn new(limit: usize) -> Windows {
        Windows {
            limit,
            held: Vec::new(),
            clock: 0,
        }
    }

    /// Whether places are reached through windows at all.
    pub(crate) fn enabled(&self) -> bool {
        self.limit > 0
    }

    /// The place `offset` bytes from `area` as a register and a one-byte displacement: the
    /// window's register if it is held, else one made by `make(offset of its middle)`, the
    /// least recently used window making room.
    pub(crate) fn reach(
        &mut self,
        area: Value,
        offset: i32,
        make: impl FnOnce(i32) -> Value,
    ) -> (Value, i32) {
        let (number, middle) = window_of(offset);
        self.clock += 1;
        let clock = self.clock;
        if let Some(window) = self
            .held
            .iter_mut()
            .find(|w| w.area == area && w.number == number)
        {
            window.used = clock;
            return (window.register, offset - middle);
        }
        if self.held.len() >= self.limit {
            let oldest = (0..self.held.len()).min_by_key(|&k| self.held[k].used);
            if let Some(oldest) = oldest {
                self.held.swap_remove(oldest);
            }
        }
        let register = make(middle);
        self.held.push(Window {
            area,
            number,
            register,
            used: clock,
        });
        (register, offset - middle)
    }

    /// The numbers of `area`'s held windows, most recently used first: where a new spill is
    /// best placed.
    pub(crate) fn held_of(&self, area: Value) -> Vec<i32> {
        let mut held: Vec<&Window> = self.held.iter().filter(|w| w.area == area).collect();
        held.sort_by_key(|w| std::cmp::Reverse(w.used));
        held.iter().map(|w| w.number).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use cranelift_codegen::entity::EntityRef;

    /// Every place's displacement from its window's middle fits one byte, and the middle plus
    /// the displacement is the place: the address does not change.
    #[test]
    fn every_place_is_a_one_byte_displacement_from_its_window() {
        for offset in (0..5000).chain([-300, -129, -128, -1]) {
            let (_, middle) = window_of(offset);
            let displacement = offset - middle;
            assert!((-128..=127).contains(&displacement), "{offset}");
            assert_eq!(middle + displacement, offset);
        }
        assert_eq!(window_of(255).0, window_of(0).0);
        assert_ne!(window_of(256).0, window_of(255).0);
    }

    /// A window is made once while held, per area; at the limit the least recently used one
    /// is dropped and made again when reached.
    #[test]
    fn windows_are_made_once_while_held_and_the_least_recently_used_makes_room() {
        let (a, b) = (Value::new(0), Value::new(1));
        let mut windows = Windows::new(2);
        let mut made = Vec::new();
        let mut next = 100;
        let mut reach = |w: &mut Windows, area: Value, offset: i32, made: &mut Vec<i32>| {
            w.reach(area, offset, |middle| {
                made.push(middle);
                next += 1;
                Value::new(next)
            })
        };
        let (first, at) = reach(&mut windows, a, 16, &mut made);
        assert_eq!(at, 16 - 128);
        assert_eq!(reach(&mut windows, a, 200, &mut made).0, first);
        reach(&mut windows, b, 16, &mut made);
        assert_eq!(made, [128, 128], "one window of each area");
        assert_eq!(windows.held_of(a), [0]);
        reach(&mut windows, a, 0, &mut made);
        reach(&mut windows, a, 600, &mut made);
        assert_eq!(
            made,
            [128, 128, 640],
            "b's window, least recently used, made room"
        );
        assert_eq!(windows.held_of(a), [2, 0]);
        assert!(windows.held_of(b).is_empty());
    }
}
