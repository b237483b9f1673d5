//! A bound on the work of expanding and printing: what keeps `rne show` of a robot whose
//! equations run to gigabytes a matter of seconds.

/// Work allowed, in term operations: one unit is one term of a product's pairs, of a sum's
/// operands, of a copy, or one harmonic of a printed term
/// ([`Polynomial::from_exprs_within`](super::Polynomial::from_exprs_within),
/// [`Printer::print_within`](super::Printer::print_within)). Every such operation is a
/// `BTreeMap` insertion or merge, so the time taken is proportional to the work spent,
/// whatever the expressions. Work that would pass what is left is refused whole, not begun.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct WorkBudget {
    limit: usize,
    spent: usize,
    refused: bool,
}

impl WorkBudget {
    /// At most `limit` units of work.
    pub fn new(limit: usize) -> WorkBudget {
        WorkBudget {
            limit,
            spent: 0,
            refused: false,
        }
    }

    /// No bound.
    pub fn unlimited() -> WorkBudget {
        WorkBudget::new(usize::MAX)
    }

    /// Takes `units` if that many are left, and says whether it did; once some work has been
    /// refused, [`exhausted`](WorkBudget::exhausted) says so.
    pub fn spend(&mut self, units: usize) -> bool {
        if units > self.left() {
            self.refused = true;
            return false;
        }
        self.spent += units;
        true
    }

    /// Takes on the work a part of this budget (made from what it had left) spent, and its
    /// refusals.
    pub fn absorb(&mut self, part: &WorkBudget) {
        self.spent = self.spent.saturating_add(part.spent).min(self.limit);
        self.refused |= part.refused;
    }

    /// Units left.
    pub fn left(&self) -> usize {
        self.limit - self.spent
    }

    /// Units spent so far.
    pub fn spent(&self) -> usize {
        self.spent
    }

    /// Whether some work was refused for want of units.
    pub fn exhausted(&self) -> bool {
        self.refused
    }
}

#[cfg(test)]
mod tests {
    use super::WorkBudget;

    #[test]
    fn work_past_what_is_left_is_refused_whole_and_remembered() {
        let mut budget = WorkBudget::new(10);
        assert!(budget.spend(7));
        assert!(!budget.exhausted());
        assert!(!budget.spend(4), "4 units with 3 left");
        assert_eq!(budget.spent(), 7, "refused work costs nothing");
        assert!(budget.exhausted());
        assert!(budget.spend(3));
        assert_eq!(budget.left(), 0);
        assert!(WorkBudget::unlimited().spend(usize::MAX));
        let mut whole = WorkBudget::new(10);
        let mut part = WorkBudget::new(whole.left() / 2);
        assert!(part.spend(4) && !part.spend(2));
        whole.absorb(&part);
        assert_eq!((whole.spent(), whole.exhausted()), (4, true));
    }
}
