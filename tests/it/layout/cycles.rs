//! The cycle finder: the strongly connected components of a directed graph (Tarjan 1972), each
//! reported as one cycle through its nodes, so a failure names the files or folders that import
//! each other.

use std::collections::{BTreeMap, BTreeSet};

/// A directed graph over named nodes: each node and the nodes it points to.
pub type Graph = BTreeMap<String, BTreeSet<String>>;

/// One cycle per strongly connected component of more than one node (or a node with an edge to
/// itself), each as its nodes in edge order with the first repeated at the end
/// (`["a", "b", "a"]`); empty when the graph has no cycle.
pub fn cycles(graph: &Graph) -> Vec<Vec<String>> {
    components(graph)
        .into_iter()
        .filter(|c| c.len() > 1 || graph.get(&c[0]).is_some_and(|e| e.contains(&c[0])))
        .map(|c| cycle_within(graph, &c.into_iter().collect()))
        .collect()
}

/// The strongly connected components, each sorted by name.
fn components(graph: &Graph) -> Vec<Vec<String>> {
    struct Tarjan<'g> {
        graph: &'g Graph,
        next: usize,
        index: BTreeMap<&'g str, usize>,
        low: BTreeMap<&'g str, usize>,
        stack: Vec<&'g str>,
        on_stack: BTreeSet<&'g str>,
        out: Vec<Vec<String>>,
    }
    impl<'g> Tarjan<'g> {
        fn visit(&mut self, v: &'g str) {
            self.index.insert(v, self.next);
            self.low.insert(v, self.next);
            self.next += 1;
            self.stack.push(v);
            self.on_stack.insert(v);
            for w in self.graph.get(v).into_iter().flatten() {
                let w = w.as_str();
                if !self.index.contains_key(w) {
                    self.visit(w);
                    let low = self.low[v].min(self.low[w]);
                    self.low.insert(v, low);
                } else if self.on_stack.contains(w) {
                    let low = self.low[v].min(self.index[w]);
                    self.low.insert(v, low);
                }
            }
            if self.low[v] == self.index[v] {
                let mut component = Vec::new();
                while let Some(w) = self.stack.pop() {
                    self.on_stack.remove(w);
                    component.push(w.to_owned());
                    if w == v {
                        break;
                    }
                }
                component.sort();
                self.out.push(component);
            }
        }
    }
    let mut t = Tarjan {
        graph,
        next: 0,
        index: BTreeMap::new(),
        low: BTreeMap::new(),
        stack: Vec::new(),
        on_stack: BTreeSet::new(),
        out: Vec::new(),
    };
    for v in graph.keys() {
        if !t.index.contains_key(v.as_str()) {
            t.visit(v);
        }
    }
    t.out
}

/// A cycle through the first node of a strongly connected component `nodes`: the shortest path
/// back to it found breadth first, staying inside the component.
fn cycle_within(graph: &Graph, nodes: &BTreeSet<String>) -> Vec<String> {
    let start = nodes.iter().next().expect("a component has a node");
    let mut came_from: BTreeMap<&str, &str> = BTreeMap::new();
    let mut frontier = vec![start.as_str()];
    while !frontier.is_empty() {
        let mut next = Vec::new();
        for v in frontier {
            for w in graph.get(v).into_iter().flatten() {
                if w == start {
                    let mut path = vec![start.clone(), v.to_owned()];
                    let mut at = v;
                    while at != start {
                        at = came_from[at];
                        path.push(at.to_owned());
                    }
                    path.reverse();
                    return path;
                }
                if nodes.contains(w) && !came_from.contains_key(w.as_str()) {
                    came_from.insert(w, v);
                    next.push(w.as_str());
                }
            }
        }
        frontier = next;
    }
    unreachable!("a strongly connected component of more than one node holds a cycle")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn graph(edges: &[(&str, &str)]) -> Graph {
        let mut g = Graph::new();
        for &(a, b) in edges {
            g.entry(a.into()).or_default().insert(b.into());
            g.entry(b.into()).or_default();
        }
        g
    }

    #[test]
    fn a_tree_and_a_diamond_have_no_cycle() {
        let g = graph(&[("a", "b"), ("a", "c"), ("b", "d"), ("c", "d")]);
        assert!(cycles(&g).is_empty());
    }

    #[test]
    fn two_nodes_importing_each_other_are_named() {
        let g = graph(&[("a", "b"), ("b", "a"), ("b", "c")]);
        assert_eq!(cycles(&g), vec![vec!["a", "b", "a"]]);
    }

    #[test]
    fn a_longer_loop_and_a_self_loop_are_found_apart() {
        let g = graph(&[("a", "b"), ("b", "c"), ("c", "a"), ("d", "d"), ("c", "d")]);
        assert_eq!(
            cycles(&g),
            vec![vec!["d", "d"], vec!["a", "b", "c", "a"]],
            "one cycle per component"
        );
    }
}
