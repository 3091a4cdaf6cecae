//! The best-first branch-and-bound engine that every certified search of this crate
//! (and the constraint search of the code that uses it) runs on.
//!
//! A search is a [`Problem`]: nodes (boxes of samples, say) carry a key, a lower bound
//! of what the search minimises over the node. The engine keeps the open nodes in a
//! [`Frontier`] and hands the node of smallest key to [`Problem::visit`], which decides
//! it: drop it, record something about it, push children into the frontier, or stop the
//! whole search. Because the node of smallest key is always taken first, that key is a
//! lower bound over everything still open; a problem reads it to certify its answer.
//!
//! Ties between equal keys are broken by a fixed rule ([`Ties`]), never by anything
//! that depends on timing, so a search is deterministic.

use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// How nodes of equal key are ordered.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Ties {
    /// The deepest node first, so that ties (common when keys are split points) dive
    /// rather than sweep.
    Deepest,
    /// No preference: the heap's own order.
    Heap,
}

/// One open node with its key and its depth in the split tree.
#[derive(Clone, Debug)]
pub struct Open<T> {
    pub key: f64,
    pub depth: u32,
    pub node: T,
}

struct Entry<T> {
    open: Open<T>,
    deepest: bool,
}

impl<T> PartialEq for Entry<T> {
    fn eq(&self, o: &Self) -> bool {
        self.cmp(o) == Ordering::Equal
    }
}
impl<T> Eq for Entry<T> {}
impl<T> PartialOrd for Entry<T> {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}
impl<T> Ord for Entry<T> {
    fn cmp(&self, o: &Self) -> Ordering {
        // BinaryHeap is a max-heap: the smallest key comes out first.
        let by_key = o.open.key.partial_cmp(&self.open.key).unwrap_or(Ordering::Equal);
        if self.deepest {
            by_key.then(self.open.depth.cmp(&o.open.depth))
        } else {
            by_key
        }
    }
}

/// The open nodes of a search, smallest key first.
pub struct Frontier<T> {
    heap: BinaryHeap<Entry<T>>,
    ties: Ties,
}

impl<T> Frontier<T> {
    pub fn new(ties: Ties) -> Self {
        Frontier { heap: BinaryHeap::new(), ties }
    }
    /// Open a node.
    pub fn push(&mut self, key: f64, depth: u32, node: T) {
        self.heap.push(Entry { open: Open { key, depth, node }, deepest: self.ties == Ties::Deepest });
    }
    /// Take the node of smallest key.
    pub fn pop(&mut self) -> Option<Open<T>> {
        self.heap.pop().map(|e| e.open)
    }
    /// Close every node, returning their keys (in no particular order).
    pub fn drain_keys(&mut self) -> Vec<f64> {
        self.heap.drain().map(|e| e.open.key).collect()
    }
    /// Close every node.
    pub fn clear(&mut self) {
        self.heap.clear();
    }
    pub fn len(&self) -> usize {
        self.heap.len()
    }
    pub fn is_empty(&self) -> bool {
        self.heap.is_empty()
    }
}

/// What a visit decided about the search as a whole.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Flow {
    /// Go on with the next node.
    Continue,
    /// The search is over (answered, or out of budget): the frontier is left as it is.
    Stop,
}

/// A search the engine runs.
pub trait Problem {
    type Node;
    /// Decide the open node of smallest key: drop it, record it, push its children into
    /// `frontier`, or stop.
    fn visit(&mut self, open: Open<Self::Node>, frontier: &mut Frontier<Self::Node>) -> Flow;
}

/// How a run ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Ending {
    /// Every node was decided.
    Exhausted,
    /// A visit stopped the search.
    Stopped,
}

/// Run `problem` from the nodes already in `frontier` until it is empty or a visit
/// stops it.
pub fn run<P: Problem>(problem: &mut P, frontier: &mut Frontier<P::Node>) -> Ending {
    while let Some(open) = frontier.pop() {
        if problem.visit(open, frontier) == Flow::Stop {
            return Ending::Stopped;
        }
    }
    Ending::Exhausted
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Minimise |x - 0.3| over [0, 1] by bisection: the engine takes boxes by lower
    /// bound, so the first box narrower than 1e-3 holds the minimiser.
    struct Bisect {
        visits: u32,
        found: Option<(f64, f64)>,
    }
    impl Problem for Bisect {
        type Node = (f64, f64);
        fn visit(&mut self, open: Open<(f64, f64)>, frontier: &mut Frontier<(f64, f64)>) -> Flow {
            self.visits += 1;
            let (a, b) = open.node;
            if b - a < 1e-3 {
                self.found = Some((a, b));
                return Flow::Stop;
            }
            let m = 0.5 * (a + b);
            for (lo, hi) in [(a, m), (m, b)] {
                let key = if lo <= 0.3 && 0.3 <= hi { 0.0 } else { (lo - 0.3).abs().min((hi - 0.3).abs()) };
                frontier.push(key, open.depth + 1, (lo, hi));
            }
            Flow::Continue
        }
    }

    #[test]
    fn smallest_key_first_finds_the_minimiser() {
        let mut p = Bisect { visits: 0, found: None };
        let mut f = Frontier::new(Ties::Deepest);
        f.push(0.0, 0, (0.0, 1.0));
        assert_eq!(run(&mut p, &mut f), Ending::Stopped);
        let (a, b) = p.found.unwrap();
        assert!(a <= 0.3 && 0.3 <= b, "{a} {b}");
        // depth-first among ties: one box per level
        assert!(p.visits <= 12, "{} visits", p.visits);
    }

    #[test]
    fn ties_go_deepest_first_or_by_the_heap() {
        let mut f = Frontier::new(Ties::Deepest);
        f.push(1.0, 0, 'a');
        f.push(1.0, 5, 'b');
        f.push(0.5, 0, 'c');
        assert_eq!(f.pop().unwrap().node, 'c');
        assert_eq!(f.pop().unwrap().node, 'b');
        assert_eq!(f.pop().unwrap().node, 'a');
        assert!(f.is_empty());
        let mut f = Frontier::new(Ties::Heap);
        f.push(2.0, 0, 'a');
        f.push(1.0, 0, 'b');
        assert_eq!(f.len(), 2);
        assert_eq!(f.drain_keys().len(), 2);
        assert!(f.pop().is_none());
    }
}
