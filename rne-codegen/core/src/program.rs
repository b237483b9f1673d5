//! The straight-line program a kernel is emitted from, and its lowering from the graph.
//!
//! Lowering turns the hash-consed DAG (where common subexpressions are already shared and
//! constants folded) into SSA instructions in topological order, absorbing negations into
//! subtractions: `a + (−b)` becomes `a − b`, and a negation is only computed when something
//! other than an addition uses it. Only the nodes the outputs need are lowered (dead-code
//! elimination). [`Program::fuse_multiply_add`] then optionally fuses products into the sums
//! that use them (the `fma: true` scene setting).

use rne_symbolic::{ExprGraph, Id, Node, OpCount, Real, Symbol};

use crate::latency::instr_cycles;

#[cfg(test)]
mod filetests;
mod text;

/// An operand: a previous instruction's result, a constant or an input.
#[derive(Copy, Clone, Debug, PartialEq)]
pub enum Operand {
    /// The result of instruction `i`.
    Temp(u32),
    /// A constant.
    Const(f64),
    /// A joint variable or a runtime parameter.
    Input(Symbol),
    /// Lane `lane` of the vector result of instruction `temp` (an output of a program whose
    /// values read [`Symbol::Lane`]: [`Program::pick_lanes`]).
    Lane {
        /// The instruction.
        temp: u32,
        /// The lane.
        lane: u8,
    },
}

impl Operand {
    /// The instruction whose result this operand reads, if any.
    pub fn temp(self) -> Option<u32> {
        match self {
            Operand::Temp(t) | Operand::Lane { temp: t, .. } => Some(t),
            Operand::Const(_) | Operand::Input(_) => None,
        }
    }
}

/// One operation.
#[derive(Copy, Clone, Debug, PartialEq)]
pub enum Instr {
    /// `a + b`.
    Add(Operand, Operand),
    /// `a − b`.
    Sub(Operand, Operand),
    /// `a · b`.
    Mul(Operand, Operand),
    /// `a / b`.
    Div(Operand, Operand),
    /// `−a`.
    Neg(Operand),
    /// `sin a`.
    Sin(Operand),
    /// `cos a`.
    Cos(Operand),
    /// `sqrt a`.
    Sqrt(Operand),
    /// `sign a`.
    Sign(Operand),
    /// `a · b + c`, through the runtime's `Real::mul_add`.
    MulAdd(Operand, Operand, Operand),
    /// `a · b − c`, as `mul_add(a, b, −c)`.
    MulSub(Operand, Operand, Operand),
    /// `c − a · b`, as `mul_add(−a, b, c)`.
    NegMulAdd(Operand, Operand, Operand),
}

impl Instr {
    /// The operands, in order.
    pub fn operands(&self) -> impl Iterator<Item = Operand> {
        let (a, b, c) = match *self {
            Instr::Add(a, b) | Instr::Sub(a, b) | Instr::Mul(a, b) | Instr::Div(a, b) => {
                (a, Some(b), None)
            }
            Instr::Neg(a) | Instr::Sin(a) | Instr::Cos(a) | Instr::Sqrt(a) | Instr::Sign(a) => {
                (a, None, None)
            }
            Instr::MulAdd(a, b, c) | Instr::MulSub(a, b, c) | Instr::NegMulAdd(a, b, c) => {
                (a, Some(b), Some(c))
            }
        };
        std::iter::once(a).chain(b).chain(c)
    }

    /// The same operation on the operands `f` maps these to.
    pub fn map_operands(self, mut f: impl FnMut(Operand) -> Operand) -> Instr {
        match self {
            Instr::Add(a, b) => Instr::Add(f(a), f(b)),
            Instr::Sub(a, b) => Instr::Sub(f(a), f(b)),
            Instr::Mul(a, b) => Instr::Mul(f(a), f(b)),
            Instr::Div(a, b) => Instr::Div(f(a), f(b)),
            Instr::Neg(a) => Instr::Neg(f(a)),
            Instr::Sin(a) => Instr::Sin(f(a)),
            Instr::Cos(a) => Instr::Cos(f(a)),
            Instr::Sqrt(a) => Instr::Sqrt(f(a)),
            Instr::Sign(a) => Instr::Sign(f(a)),
            Instr::MulAdd(a, b, c) => Instr::MulAdd(f(a), f(b), f(c)),
            Instr::MulSub(a, b, c) => Instr::MulSub(f(a), f(b), f(c)),
            Instr::NegMulAdd(a, b, c) => Instr::NegMulAdd(f(a), f(b), f(c)),
        }
    }
}

/// A straight-line program: instructions in dependency order and the outputs.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Program {
    /// Instructions; an instruction only uses earlier ones.
    pub instrs: Vec<Instr>,
    /// The values returned, in order.
    pub outputs: Vec<Operand>,
}

impl Program {
    /// Lowers the graph nodes needed by `outputs`.
    pub fn lower(graph: &ExprGraph, outputs: &[Id]) -> Program {
        let nodes = graph.reachable(outputs);
        let size = nodes.last().map_or(0, |id| id.index() + 1);
        // Whether each negation is used by something other than an addition.
        let mut negation_needed = vec![false; size];
        for &id in &nodes {
            let node = graph.node(id);
            let absorbs = matches!(node, Node::Add(..));
            for child in node.children() {
                if matches!(graph.node(child), Node::Neg(_)) {
                    negation_needed[child.index()] |= !absorbs;
                }
            }
        }
        for &o in outputs {
            if matches!(graph.node(o), Node::Neg(_)) {
                negation_needed[o.index()] = true;
            }
        }

        let mut program = Program::default();
        let mut operand: Vec<Option<Operand>> = vec![None; size];
        for &id in &nodes {
            let op = |c: Id| operand[c.index()].expect("operands are lowered first");
            let value = match graph.node(id) {
                Node::Const(c) => Operand::Const(c.value()),
                Node::Symbol(s) => Operand::Input(s),
                Node::Neg(a) => {
                    if !negation_needed[id.index()] {
                        continue;
                    }
                    program.push(Instr::Neg(op(a)))
                }
                Node::Add(a, b) => {
                    let instr = match (graph.node(a), graph.node(b)) {
                        (_, Node::Neg(nb)) => Instr::Sub(op(a), op(nb)),
                        (Node::Neg(na), _) => Instr::Sub(op(b), op(na)),
                        _ => Instr::Add(op(a), op(b)),
                    };
                    program.push(instr)
                }
                Node::Mul(a, b) => program.push(Instr::Mul(op(a), op(b))),
                Node::Div(a, b) => program.push(Instr::Div(op(a), op(b))),
                Node::Sin(a) => program.push(Instr::Sin(op(a))),
                Node::Cos(a) => program.push(Instr::Cos(op(a))),
                Node::Sqrt(a) => program.push(Instr::Sqrt(op(a))),
                Node::Sign(a) => program.push(Instr::Sign(op(a))),
            };
            operand[id.index()] = Some(value);
        }
        program.outputs = outputs
            .iter()
            .map(|o| operand[o.index()].expect("outputs are lowered"))
            .collect();
        program
    }

    /// The program with each addition or subtraction that has an operand computed by a
    /// multiplication used nowhere else fused with it: `a·b + c`, `a·b − c` and `c − a·b` become
    /// one [`Instr::MulAdd`], [`Instr::MulSub`] or [`Instr::NegMulAdd`] — unless fusing would
    /// make the sum ready later than the product and the sum apart would, by the latency model
    /// of `latency.rs`: a fused instruction waits for its addend too, so fusing a product
    /// whose addend arrives late lengthens the chain. When both operands are such products,
    /// the one giving the earlier result is fused (the later-computed one on a tie). Operation
    /// counts do not change (a fused pair counts as a multiplication and an addition);
    /// rounding does where the target fuses ([`Real::mul_add`]).
    pub fn fuse_multiply_add(&self) -> Program {
        let uses = self.use_counts();
        // When each instruction's value is ready in the fused program (a fused product's
        // entry is never read).
        let mut ready: Vec<u32> = Vec::with_capacity(self.instrs.len());
        let mut fused: Vec<Option<Instr>> = self.instrs.iter().map(|&i| Some(i)).collect();
        for (k, &instr) in self.instrs.iter().enumerate() {
            let (finish, fusion) = self.best_fusion(instr, &uses, &ready);
            if let Some((product, instr)) = fusion {
                fused[product as usize] = None;
                fused[k] = Some(instr);
            }
            ready.push(finish);
        }
        // Renumber the temporaries past the removed products.
        let mut index: Vec<u32> = Vec::with_capacity(fused.len());
        let mut program = Program::default();
        let renumber = |o: Operand, index: &[u32]| match o {
            Operand::Temp(t) => Operand::Temp(index[t as usize]),
            Operand::Lane { temp, lane } => Operand::Lane {
                temp: index[temp as usize],
                lane,
            },
            other => other,
        };
        for instr in fused {
            index.push(program.instrs.len() as u32);
            if let Some(instr) = instr {
                program
                    .instrs
                    .push(instr.map_operands(|o| renumber(o, &index)));
            }
        }
        program.outputs = self.outputs.iter().map(|&o| renumber(o, &index)).collect();
        program
    }

    /// When `instr` is ready, given when the earlier instructions are (`ready`), and the
    /// product it is fused with and the fused instruction, if fusing is worth it
    /// ([`Program::fuse_multiply_add`]). `uses`: [`Program::use_counts`].
    fn best_fusion(
        &self,
        instr: Instr,
        uses: &[u32],
        ready: &[u32],
    ) -> (u32, Option<(u32, Instr)>) {
        let at = |o: Operand| o.temp().map_or(0, |t| ready[t as usize]);
        let finish = |i: Instr| i.operands().map(at).max().unwrap_or(0) + instr_cycles(i);
        let unfused = finish(instr);
        let (x, y, subtract) = match instr {
            Instr::Add(x, y) => (x, y, false),
            Instr::Sub(x, y) => (x, y, true),
            _ => return (unfused, None),
        };
        let single_product = |o: Operand| match o {
            Operand::Temp(t) if uses[t as usize] == 1 => match self.instrs[t as usize] {
                Instr::Mul(a, b) => Some((t, a, b)),
                _ => None,
            },
            _ => None,
        };
        // (finish, product index, fused instruction) of fusing each candidate product.
        let candidate = |product: Operand, addend: Operand, first: bool| {
            single_product(product).map(|(t, a, b)| {
                let fused = match (subtract, first) {
                    (false, _) => Instr::MulAdd(a, b, addend),
                    (true, true) => Instr::MulSub(a, b, addend),
                    (true, false) => Instr::NegMulAdd(a, b, addend),
                };
                (finish(fused), t, fused)
            })
        };
        let best = [candidate(x, y, true), candidate(y, x, false)]
            .into_iter()
            .flatten()
            .filter(|&(finish, _, _)| finish <= unfused)
            .min_by_key(|&(finish, t, _)| (finish, std::cmp::Reverse(t)));
        match best {
            Some((finish, t, fused)) => (finish, Some((t, fused))),
            None => (unfused, None),
        }
    }

    fn push(&mut self, instr: Instr) -> Operand {
        self.instrs.push(instr);
        Operand::Temp(self.instrs.len() as u32 - 1)
    }

    /// The operations one call performs (each instruction once).
    pub fn op_count(&self) -> OpCount {
        let mut count = OpCount::default();
        for instr in &self.instrs {
            match instr {
                Instr::Add(..) | Instr::Sub(..) => count.add += 1,
                Instr::Mul(..) => count.mul += 1,
                Instr::Div(..) => count.div += 1,
                Instr::Neg(_) => count.neg += 1,
                Instr::Sin(_) => count.sin += 1,
                Instr::Cos(_) => count.cos += 1,
                Instr::Sqrt(_) => count.sqrt += 1,
                Instr::Sign(_) => count.sign += 1,
                Instr::MulAdd(..) | Instr::MulSub(..) | Instr::NegMulAdd(..) => {
                    count.mul += 1;
                    count.add += 1;
                }
            }
        }
        count
    }

    /// How many times each instruction's result is used (outputs count as uses).
    pub fn use_counts(&self) -> Vec<u32> {
        let mut uses = vec![0u32; self.instrs.len()];
        let operands = self
            .instrs
            .iter()
            .flat_map(Instr::operands)
            .chain(self.outputs.iter().copied());
        for t in operands.filter_map(Operand::temp) {
            uses[t as usize] += 1;
        }
        uses
    }

    /// Whether each instruction's result is a vector: it reads a [`Symbol::Lane`] or another
    /// vector result. The others are scalars, the same in every lane.
    pub fn vector_results(&self) -> Vec<bool> {
        let mut vector: Vec<bool> = Vec::with_capacity(self.instrs.len());
        for instr in &self.instrs {
            let reads_vector = instr.operands().any(|o| match o {
                Operand::Input(Symbol::Lane(_)) => true,
                other => other.temp().is_some_and(|t| vector[t as usize]),
            });
            vector.push(reads_vector);
        }
        vector
    }

    /// Whether the program computes with vectors ([`Program::vector_results`]).
    pub fn has_lanes(&self) -> bool {
        self.instrs
            .iter()
            .flat_map(Instr::operands)
            .any(|o| matches!(o, Operand::Input(Symbol::Lane(_))))
    }

    /// The program whose outputs are `picks`, each (output `k` of this program, lane `l`):
    /// lane l of that output where it is a vector, the output itself where it is the same in
    /// every lane. How a kernel built in lanes ([`rne_symbolic::dynamics::LanePartials`])
    /// returns each derivative from the vector that carries it.
    pub fn pick_lanes(mut self, picks: &[(usize, u8)]) -> Program {
        let vector = self.vector_results();
        self.outputs = picks
            .iter()
            .map(|&(k, lane)| match self.outputs[k] {
                Operand::Temp(temp) if vector[temp as usize] => Operand::Lane { temp, lane },
                other => other,
            })
            .collect();
        self
    }

    /// Evaluates the program in any [`Real`] scalar, operation by operation as the emitted Rust
    /// does — in `f64` the results are bit-for-bit those of the generated function. A program
    /// with lanes is evaluated once per lane its outputs pick, [`Symbol::Lane`] reading 1 in
    /// its own lane and 0 in the others, as the emitted vectors do lane by lane.
    pub fn eval<T: Real>(&self, input: impl Fn(Symbol) -> T) -> Vec<T> {
        if !self.has_lanes() {
            return self.eval_lane(&input, 0);
        }
        let lanes = (0..=u8::MAX).take_while(|&l| {
            l == 0
                || self
                    .outputs
                    .iter()
                    .any(|o| matches!(*o, Operand::Lane { lane, .. } if lane >= l))
        });
        let by_lane: Vec<Vec<T>> = lanes.map(|l| self.eval_lane(&input, l)).collect();
        (0..self.outputs.len())
            .map(|k| match self.outputs[k] {
                Operand::Lane { lane, .. } => by_lane[lane as usize][k],
                _ => by_lane[0][k],
            })
            .collect()
    }

    /// [`Program::eval`] in `f64`, instantiated here: a caller's build evaluates at this
    /// crate's optimisation level (the tests' debug builds evaluate programs of tens of
    /// thousands of instructions at many states).
    pub fn eval_f64(&self, input: &dyn Fn(Symbol) -> f64) -> Vec<f64> {
        self.eval(input)
    }

    /// The outputs in lane `lane` (an output picking a lane is read in this one).
    fn eval_lane<T: Real>(&self, input: &impl Fn(Symbol) -> T, lane: u8) -> Vec<T> {
        let mut temps: Vec<T> = Vec::with_capacity(self.instrs.len());
        let value = |o: Operand, temps: &[T]| match o {
            Operand::Temp(t) | Operand::Lane { temp: t, .. } => temps[t as usize],
            Operand::Const(c) => T::from_f64(c),
            Operand::Input(Symbol::Lane(l)) => {
                T::from_f64(f64::from(u8::from(l == u16::from(lane))))
            }
            Operand::Input(s) => input(s),
        };
        for instr in &self.instrs {
            let v = |o| value(o, &temps);
            let x = match *instr {
                Instr::Add(a, b) => v(a) + v(b),
                Instr::Sub(a, b) => v(a) - v(b),
                Instr::Mul(a, b) => v(a) * v(b),
                Instr::Div(a, b) => v(a) / v(b),
                Instr::Neg(a) => -v(a),
                Instr::Sin(a) => v(a).sin(),
                Instr::Cos(a) => v(a).cos(),
                Instr::Sqrt(a) => v(a).sqrt(),
                Instr::Sign(a) => v(a).sign(),
                Instr::MulAdd(a, b, c) => v(a).mul_add(v(b), v(c)),
                Instr::MulSub(a, b, c) => v(a).mul_add(v(b), -v(c)),
                Instr::NegMulAdd(a, b, c) => (-v(a)).mul_add(v(b), v(c)),
            };
            temps.push(x);
        }
        self.outputs.iter().map(|&o| value(o, &temps)).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::{Instr, Operand, Program};
    use rne_symbolic::{ExprGraph, Symbol, SymbolTable};

    fn lowered(text: &str) -> Program {
        let mut g = ExprGraph::new(SymbolTable::with_joints(["x", "y", "z"]));
        let root = g.parse_sexpr(text).unwrap();
        Program::lower(&g, &[root])
    }

    fn at(point: [f64; 3]) -> impl Fn(Symbol) -> f64 {
        move |s| match s {
            Symbol::Position(k) => point[k as usize],
            _ => f64::NAN,
        }
    }

    /// A program reading lane seeds computes vectors: `x·e₀ + y·e₁` is (x, y, 0, 0), and its
    /// outputs pick lanes of it; a value the same in every lane (`x·y`) is not a vector and
    /// is returned whole, whichever lane is picked.
    #[test]
    fn lanes_of_vector_results_are_picked_and_scalars_stay_whole() {
        let mut g = ExprGraph::new(SymbolTable::with_joints(["x", "y"]));
        let (x, y) = (g.symbol(Symbol::Position(0)), g.symbol(Symbol::Position(1)));
        let (e0, e1) = (g.symbol(Symbol::Lane(0)), g.symbol(Symbol::Lane(1)));
        let (xe0, ye1) = (g.mul(x, e0), g.mul(y, e1));
        let vector = g.add(xe0, ye1);
        let scalar = g.mul(x, y);
        let program = Program::lower(&g, &[vector, scalar]);
        assert_eq!(program.vector_results(), vec![true, true, true, false]);
        let picked = program.pick_lanes(&[(0, 0), (0, 1), (0, 2), (1, 3)]);
        assert!(picked.has_lanes());
        assert!(matches!(picked.outputs[1], Operand::Lane { lane: 1, .. }));
        assert!(matches!(picked.outputs[3], Operand::Temp(3)));
        assert_eq!(
            picked.eval(at([3.0, -2.0, 0.0])),
            vec![3.0, -2.0, 0.0, -6.0]
        );
    }

    /// `a·b + c`, `a·b − c` and `c − a·b` each become one fused instruction; counts stay.
    #[test]
    fn sums_of_single_use_products_fuse() {
        let x = Operand::Input(Symbol::Position(0));
        let y = Operand::Input(Symbol::Position(1));
        let z = Operand::Input(Symbol::Position(2));
        for (text, expected) in [
            ("(+ (* x y) z)", Instr::MulAdd(x, y, z)),
            ("(- (* x y) z)", Instr::MulSub(x, y, z)),
            ("(- z (* x y))", Instr::NegMulAdd(x, y, z)),
        ] {
            let program = lowered(text);
            let fused = program.fuse_multiply_add();
            assert_eq!(fused.instrs, vec![expected], "{text}");
            assert_eq!(fused.outputs, vec![Operand::Temp(0)]);
            assert_eq!(fused.op_count(), program.op_count(), "{text}");
        }
    }

    /// A product whose addend is ready long after it is not fused: the fused instruction
    /// would wait for the addend and then take longer than the addition alone; with an
    /// addend ready early it is fused.
    #[test]
    fn a_product_is_not_fused_with_a_late_addend() {
        let late = lowered("(+ (* x y) (sin (sin z)))").fuse_multiply_add();
        assert!(
            late.instrs.iter().all(|i| !matches!(i, Instr::MulAdd(..))),
            "{:?}",
            late.instrs
        );
        let early = lowered("(+ (* (sin (sin z)) y) x)").fuse_multiply_add();
        assert!(
            early.instrs.iter().any(|i| matches!(i, Instr::MulAdd(..))),
            "{:?}",
            early.instrs
        );
        assert!(early.critical_path() < lowered("(+ (* (sin (sin z)) y) x)").critical_path());
    }

    /// A product that something else also uses stays a product (fusing it would compute it
    /// twice), temporaries are renumbered past the fused ones, and the value is kept (bit for
    /// bit where the target does not fuse, to rounding where it does).
    #[test]
    fn shared_products_stay_and_values_are_kept() {
        let text = "(+ (* (+ (* x y) z) (* x y)) (- (* y z) (* z z)))";
        let program = lowered(text);
        let fused = program.fuse_multiply_add();
        let products = |p: &Program| {
            p.instrs
                .iter()
                .filter(|i| matches!(i, Instr::Mul(..)))
                .count()
        };
        let fused_count = fused
            .instrs
            .iter()
            .filter(|i| {
                matches!(
                    i,
                    Instr::MulAdd(..) | Instr::MulSub(..) | Instr::NegMulAdd(..)
                )
            })
            .count();
        assert_eq!(products(&fused) + fused_count, products(&program));
        assert_eq!(fused.op_count(), program.op_count());
        assert!(fused.instrs.iter().any(|i| matches!(i, Instr::MulAdd(..))));
        for (k, instr) in fused.instrs.iter().enumerate() {
            for operand in instr.operands() {
                if let Operand::Temp(t) = operand {
                    assert!((t as usize) < k, "{instr:?} reads a later temporary");
                }
            }
        }
        for point in [[0.3, -1.2, 2.5], [1.0, 2.0, -0.5]] {
            let (a, b) = (program.eval(at(point))[0], fused.eval(at(point))[0]);
            assert!((a - b).abs() <= 4.0 * f64::EPSILON * a.abs(), "{a} vs {b}");
        }
    }
}
