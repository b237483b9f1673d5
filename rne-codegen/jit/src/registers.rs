//! Which of a function's values are held in registers, chosen while it is lowered, so that
//! Cranelift's allocator is never handed more live values than the processor has registers.
//!
//! A straight-line program leaves its allocator one choice: which value to spill when too many
//! are alive. Belady's rule (*A study of replacement algorithms for a virtual-storage
//! computer*, IBM Systems Journal, 1966) gives the fewest reloads in a fixed order: when a
//! value must make room, take the one read again furthest ahead. Cranelift's allocator splits
//! live ranges by its own costs and, on the derivative kernels, spills and reloads about twice
//! as often (docs/performance.md, "Spilled by the lowering"). The lowering therefore keeps at
//! most [`HELD`] of its values in registers: an evicted value is stored once to a slot of the
//! function's spill area (unless it already has a place in memory: a scratch slot, the sines'
//! and cosines' array) and loaded again just before its next reader, by a plain load from the
//! area's address, which Cranelift folds into the reading operation when it is the load's only
//! reader and the operation's own value is read once. This decides where values live, never
//! what is computed: the bits are the program's.

use rne_codegen_core::{Operand, Program};
use rustc_hash::FxHashMap;

/// The most instruction values held in registers at once: x86-64 has 16 vector registers,
/// AArch64 32; the inputs, constants and the operations' own temporaries take the rest. On
/// x86-64, 14 ran the derivative kernels fastest of 8, 10, 12, 13, 14, 16 and 24
/// (docs/performance.md, "Spilled by the lowering"); AArch64's is the same margin, unmeasured.
pub(crate) const HELD: usize = if cfg!(target_arch = "aarch64") {
    28
} else {
    14
};

/// [`HELD`], or as `RNE_JIT_HELD` says (a positive number; for measuring other limits).
pub(crate) fn held_limit() -> usize {
    std::env::var("RNE_JIT_HELD")
        .ok()
        .and_then(|n| n.parse::<usize>().ok())
        .filter(|&n| n > 0)
        .unwrap_or(HELD)
}

/// The values held and where each value is read next.
pub(crate) struct Registers {
    limit: usize,
    /// The first instruction of the function: its own values are numbered from it.
    start: usize,
    /// The values of earlier functions read here, numbered after the function's own.
    earlier: FxHashMap<usize, usize>,
    /// For each numbered value, where its reads begin in `reads`; one more entry at the end.
    first: Vec<u32>,
    /// The instructions reading each value, in order, value after value.
    reads: Vec<u32>,
    /// For each numbered value, how many of its reads are done.
    done: Vec<u32>,
    /// The values held, in the order they came in.
    held: Vec<usize>,
    /// The most values alive at once in the function (computed, or read from an earlier
    /// function, and read again): a bound on the values spilled at once.
    most_alive: usize,
}

impl Registers {
    /// The reads of instructions `start..end` of `program`, nothing held, at most `limit`
    /// values held.
    pub(crate) fn new(program: &Program, start: usize, end: usize, limit: usize) -> Registers {
        let own = end - start;
        let mut earlier: FxHashMap<usize, usize> = FxHashMap::default();
        let mut count: Vec<u32> = vec![0; own];
        for k in start..end {
            for &t in distinct_temps(program, k).as_slice() {
                let id = match t.checked_sub(start) {
                    Some(id) => id,
                    None => *earlier.entry(t).or_insert_with(|| {
                        count.push(0);
                        count.len() - 1
                    }),
                };
                count[id] += 1;
            }
        }
        let mut first = Vec::with_capacity(count.len() + 1);
        let mut total = 0u32;
        for &c in &count {
            first.push(total);
            total += c;
        }
        first.push(total);
        let mut registers = Registers {
            limit,
            start,
            earlier,
            first,
            reads: vec![0; total as usize],
            done: vec![0; count.len()],
            held: Vec::new(),
            most_alive: 0,
        };
        for k in start..end {
            for &t in distinct_temps(program, k).as_slice() {
                let id = registers.id(t);
                let at = registers.first[id] + registers.done[id];
                registers.reads[at as usize] = k as u32;
                registers.done[id] += 1;
            }
        }
        registers.done.fill(0);
        registers.most_alive = registers.count_most_alive(own);
        registers
    }

    /// The most values alive at once over the function's `own` instructions.
    fn count_most_alive(&self, own: usize) -> usize {
        // change[k]: values that come alive at instruction k, less those read last at k − 1.
        let mut change = vec![0i64; own + 1];
        for id in 0..self.done.len() {
            let (first, end) = (self.first[id] as usize, self.first[id + 1] as usize);
            if first == end {
                continue;
            }
            let from = if id < own { id } else { 0 };
            let last = self.reads[end - 1] as usize - self.start;
            change[from] += 1;
            change[last + 1] -= 1;
        }
        let mut alive = 0i64;
        let mut most = 0i64;
        for c in change {
            alive += c;
            most = most.max(alive);
        }
        most as usize
    }

    /// The most values alive at once in the function: no more can be spilled at once.
    pub(crate) fn most_alive(&self) -> usize {
        self.most_alive
    }

    /// Value `t`'s number.
    fn id(&self, t: usize) -> usize {
        match t.checked_sub(self.start) {
            Some(id) => id,
            None => self.earlier[&t],
        }
    }

    /// Where value `t` is read next, `u32::MAX` if nowhere.
    fn next_read(&self, t: usize) -> u32 {
        let id = self.id(t);
        let at = self.first[id] + self.done[id];
        if at < self.first[id + 1] {
            self.reads[at as usize]
        } else {
            u32::MAX
        }
    }

    /// Whether value `t` is read again in this function.
    pub(crate) fn is_read_again(&self, t: usize) -> bool {
        self.next_read(t) != u32::MAX
    }

    /// The values to evict so that `incoming` more fit, the ones read furthest ahead first,
    /// never one of `keep` (the operands of the instruction about to be lowered). They are no
    /// longer held when this returns.
    pub(crate) fn make_room(&mut self, incoming: usize, keep: &[usize]) -> Vec<usize> {
        let mut evicted = Vec::new();
        while self.held.len() + incoming > self.limit {
            let furthest = self
                .held
                .iter()
                .enumerate()
                .filter(|(_, t)| !keep.contains(t))
                .max_by_key(|(_, &t)| self.next_read(t))
                .map(|(k, _)| k);
            let Some(k) = furthest else { break };
            evicted.push(self.held.remove(k));
        }
        evicted
    }

    /// Value `t` is now in a register.
    pub(crate) fn hold(&mut self, t: usize) {
        self.held.push(t);
    }

    /// Value `t` was read by the instruction being lowered: whether that was its last read
    /// here (then it is no longer held).
    pub(crate) fn read(&mut self, t: usize) -> bool {
        let id = self.id(t);
        self.done[id] += 1;
        let last = self.first[id] + self.done[id] == self.first[id + 1];
        if last {
            self.held.retain(|&h| h != t);
        }
        last
    }
}

/// The distinct instruction values one instruction reads (at most three).
pub(crate) struct Reads {
    temps: [usize; 3],
    len: usize,
}

impl Reads {
    pub(crate) fn as_slice(&self) -> &[usize] {
        &self.temps[..self.len]
    }
}

/// The instruction values instruction `k` reads, each once.
pub(crate) fn distinct_temps(program: &Program, k: usize) -> Reads {
    let mut reads = Reads {
        temps: [0; 3],
        len: 0,
    };
    for t in program.instrs[k].operands().filter_map(Operand::temp) {
        let t = t as usize;
        if !reads.as_slice().contains(&t) {
            reads.temps[reads.len] = t;
            reads.len += 1;
        }
    }
    reads
}

#[cfg(test)]
mod tests {
    use super::Registers;
    use rne_codegen_core::{Instr, Operand, Program};
    use rne_symbolic::Symbol;

    /// t0 = x + y, t1 = x·y, t2 = x − y, t3 = t0 + t1, t4 = t2·t0: t0 is read by t3 and t4,
    /// t1 by t3, t2 by t4.
    fn program() -> Program {
        let (x, y) = (
            Operand::Input(Symbol::Position(0)),
            Operand::Input(Symbol::Position(1)),
        );
        let t = Operand::Temp;
        Program {
            instrs: vec![
                Instr::Add(x, y),
                Instr::Mul(x, y),
                Instr::Sub(x, y),
                Instr::Add(t(0), t(1)),
                Instr::Mul(t(2), t(0)),
            ],
            outputs: vec![t(3), t(4)],
        }
    }

    /// Room is made by evicting the value read furthest ahead (Belady's rule), never one the
    /// next instruction reads.
    #[test]
    fn the_value_read_furthest_ahead_makes_room() {
        let mut registers = Registers::new(&program(), 0, 5, 2);
        for t in 0..3 {
            registers.hold(t);
        }
        // t2 is read at instruction 4, t0 and t1 at 3.
        assert_eq!(registers.make_room(0, &[]), vec![2]);
        registers.hold(2);
        assert_eq!(registers.make_room(0, &[2]).len(), 1);
        assert_eq!(registers.make_room(1, &[0, 1, 2]), Vec::<usize>::new());
    }

    /// t0, t1 and t2 are alive together at instructions 2 and 3: at most three values can be
    /// spilled at once, the size of the spill area.
    #[test]
    fn the_spill_area_has_room_for_the_most_values_alive() {
        assert_eq!(Registers::new(&program(), 0, 5, 2).most_alive(), 3);
        // A function of instructions 3 and 4: t0, t1 and t2 come from an earlier function,
        // all alive at its start.
        assert_eq!(Registers::new(&program(), 3, 5, 2).most_alive(), 3);
    }

    /// A value is released at its last read, not before.
    #[test]
    fn a_value_is_released_at_its_last_read() {
        let mut registers = Registers::new(&program(), 0, 5, 4);
        for t in 0..3 {
            registers.hold(t);
        }
        assert!(!registers.read(0), "t0 is read again by t4");
        assert!(registers.read(1));
        assert!(registers.is_read_again(0) && !registers.is_read_again(1));
        assert!(registers.read(2) && registers.read(0));
        assert!(!registers.is_read_again(0));
    }
}
