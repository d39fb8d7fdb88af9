"""The automatic decomposition: the block-triangular (Dulmage-Mendelsohn) form of the body-equilibrium
system, read as ordered sub-kinematic chains (SKCs).

The system. Each moving body k gives six rows: the equilibrium of the subtree it carries (force, and
moment about k's joint origin, world axes), i.e. the virtual work of a rigid motion of everything
beyond joint k, the SOC method's virtual displacements. Each joint gives one unknown per reaction
component it can carry, plus its effort when actuated. A tree joint's wrench enters only its child's
rows; a cut joint's the rows of the bodies that carry exactly one of its sides
(`Structure.crossings`). Which entries are non-zero is read with every lever arm generic (a force
along a world axis has no moment about that axis; a point on the row's origin has no lever), and from
the wrench directions at the home assembly, so that an accidental zero of one pose is not taken for
structure.

Why Dulmage-Mendelsohn gives the finest solve order. A maximum matching of rows to unknowns
(`scipy.sparse.csgraph.maximum_bipartite_matching`) splits the system into an over-determined part
V (reached by alternating paths from unmatched rows), an under-determined part H (from unmatched
unknowns) and a perfectly matched square part S. In S, orient an edge from unknown u to unknown w
when the row matched to u involves w; the strongly connected components of that digraph are the
irreducible diagonal blocks, and a topological order of them (a block after every block whose
unknowns its rows use) is a block-triangular form. Dulmage and Mendelsohn (1958) showed that this
partition does not depend on the matching chosen and that no block can be split: every proper subset
of a block's rows involves more of the block's unknowns than it has rows. So solving block by block,
each with the earlier blocks' values as known loads, is the finest sequence in which each step fixes
exactly its own unknowns. V comes first (its rows use only its own unknowns), H last (its unknowns
appear in no other rows), each split into its connected parts.

How it maps to Yang Tingli's ordered SOCs. A square block is an SKC: a group of bodies whose
equilibrium, with the reactions from the SKCs already solved applied as known loads, fixes exactly
the reactions released at its boundary to the SKCs not yet solved (with its internal and ground
reactions) and its actuator efforts. The solve order is the reverse of the assembly order of the
ordered SOCs; a block holding one SOC's bodies has coupling degree 0, a block gathering several SOCs
that must be solved together has a positive coupling degree (the number of loop equations solved
simultaneously). Rows are components, not bodies, so the blocks can be finer than body groups: in a
linkage whose axes are all along y the in-plane rows (fx, fz, my) form their own SKCs, and the
out-of-plane rows (fy, mx, mz) the under-determined part H, whose reaction components redundant
constraints leave indeterminate.
"""

from __future__ import annotations

from collections import deque
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from scipy.sparse.csgraph import connected_components, maximum_bipartite_matching

from mechkit.base.exceptions import InvalidParameters
from mechkit.base.spatial import cross
from mechkit.second_opinion.instant import Instant
from mechkit.second_opinion.structure_graph import COMPONENT_NAMES, Structure

#: Relative size below which a wrench-direction entry counts as a structural zero.
PATTERN_TOL = 1e-9

#: Distance (relative to the mechanism's extent) below which a joint point sits on a body origin.
COINCIDENT_TOL = 1e-9

Row = tuple[int, int]  # (body id, component 0..5: force x y z, moment x y z)
Unknown = tuple[str, int]  # (joint name, index in its components; -1 = its effort)


@dataclass(frozen=True)
class SKC:
    """One block of the decomposition, in solve order.

    Attributes:
        kind: "determined" (square), "under" (more unknowns than rows: redundant constraints or
            actuation) or "over" (more rows than unknowns).
        rows: its equilibrium rows (body id, component).
        unknowns: its unknowns (joint, component index or -1 for the effort).
        bodies: names of the bodies whose rows it holds.
        joints: joints with reaction components solved here.
        released: of those, the joints to a body of an SKC not solved yet.
        actuators: joints whose effort is solved here.
        equations: independent equations (rank of its block at the home assembly).
    """

    kind: str
    rows: tuple[Row, ...]
    unknowns: tuple[Unknown, ...]
    bodies: tuple[str, ...]
    joints: tuple[str, ...]
    released: tuple[str, ...]
    actuators: tuple[str, ...]
    equations: int

    def unknown_labels(self, structure: Structure) -> list[str]:
        """Readable unknowns, e.g. "R43.fx", "R31.effort" (component names are the world wrench
        directions the component was chosen from).

        Args:
            structure: the structure graph the SKC was found in.

        Returns:
            One label per unknown, in order.
        """
        out = []
        for name, k in self.unknowns:
            joint = structure.joint(name)
            out.append(f"{name}.effort" if k < 0 else f"{name}.{COMPONENT_NAMES[joint.components[k]]}")
        return out


def unknowns_of(structure: Structure) -> list[Unknown]:
    """Every unknown of the body-equilibrium system: each joint's components, then its effort.

    Args:
        structure: the structure graph.

    Returns:
        (joint, component index, -1 for its effort) per unknown, in the system's column order.
    """
    out: list[Unknown] = []
    for joint in structure.joints:
        out.extend((joint.name, k) for k in range(len(joint.components)))
        if joint.actuated:
            out.append((joint.name, -1))
    return out


def equilibrium_matrix(
    structure: Structure, home: Instant, generic: bool
) -> tuple[list[Row], list[Unknown], np.ndarray]:
    """The subtree-equilibrium matrix at ``home``: rows (body, component) x unknowns.

    Entry: the row's component of the unknown's unit wrench on the subtree of that body (+ where the
    subtree holds the joint's child side, - where it holds the parent side), moment about the body's
    origin. With ``generic``, a 0/1 pattern instead (see the module docstring).

    Args:
        structure: the structure graph.
        home: the home assembly's instant.
        generic: the 0/1 pattern with generic lever arms instead of the values.

    Returns:
        (rows (body, component 0-5), unknowns (joint, component), the matrix (6 bodies x unknowns); N and N m per
            unit unknown).
    """
    rows = [(b, k) for b in structure.bodies for k in range(6)]
    points = np.array([g.point for g in home.joints.values()] + [b.origin for b in home.bodies.values()])
    coincident = COINCIDENT_TOL * max(float(np.ptp(points, axis=0).max()), 1e-3)
    where = {r: i for i, r in enumerate(rows)}
    cols = unknowns_of(structure)
    matrix = np.zeros((len(rows), len(cols)))
    for c, (name, k) in enumerate(cols):
        joint, geometry = structure.joint(name), home.joints[name]
        wrench = geometry.effort if k < 0 else geometry.basis[:, k]
        nonzero = np.abs(wrench) > PATTERN_TOL * np.abs(wrench).max()
        for body, sign in structure.crossings(joint).items():
            i = where[(body, 0)]
            lever = geometry.point - home.bodies[body].origin
            if not generic:
                matrix[i : i + 6, c] = sign * np.concatenate([wrench[:3], wrench[3:] + cross(lever, wrench[:3])])
                continue
            at_origin = (not joint.cut and body == joint.child) or np.linalg.norm(lever) <= coincident
            force_moment = np.array([np.delete(nonzero[:3], a).any() for a in range(3)]) & (not at_origin)
            matrix[i : i + 6, c] = np.concatenate([nonzero[:3], nonzero[3:] | force_moment])
    return rows, cols, matrix


def _reach(start: list[int], adjacency: sp.csr_matrix, back: np.ndarray) -> tuple[set[int], set[int]]:
    """Alternating-path reach: from ``start`` nodes along ``adjacency`` then back along the matching."""
    seen_here, seen_there = set(start), set()
    queue = deque(start)
    while queue:
        node = queue.popleft()
        for other in adjacency.indices[adjacency.indptr[node] : adjacency.indptr[node + 1]]:
            if other in seen_there:
                continue
            seen_there.add(int(other))
            mate = int(back[other])
            if mate >= 0 and mate not in seen_here:
                seen_here.add(mate)
                queue.append(mate)
    return seen_here, seen_there


def _parts(rows: list[int], cols: list[int], pattern: sp.csr_matrix) -> list[tuple[list[int], list[int]]]:
    """Connected parts of the bipartite sub-graph (rows, cols), ordered by their first row."""
    if not rows and not cols:
        return []
    sub = pattern[rows][:, cols]
    m = len(rows)
    graph = sp.bmat([[sp.csr_matrix((m, m)), sub], [sub.T, sp.csr_matrix((len(cols), len(cols)))]], format="csr")
    count, labels = connected_components(graph, directed=False)
    parts = [
        ([rows[i] for i in range(m) if labels[i] == p], [cols[j] for j in range(len(cols)) if labels[m + j] == p])
        for p in range(count)
    ]
    return sorted(parts, key=lambda part: min(part[0], default=len(pattern.indptr)))


def block_triangular(pattern: sp.csr_matrix) -> list[tuple[str, list[int], list[int]]]:
    """Dulmage-Mendelsohn blocks of a sparse pattern (rows x cols), in solve order.

    Args:
        pattern: a sparse (rows x cols) pattern; its non-zeros are the entries.

    Returns:
        (kind, rows, cols) per block: the over-determined parts ("over"), the irreducible square
        blocks ("determined") in an order where each block's rows use only its own and earlier
        blocks' columns, then the under-determined parts ("under").
    """
    pattern = sp.csr_matrix(pattern, dtype=float)
    pattern.eliminate_zeros()
    m, n = pattern.shape
    col_of_row = maximum_bipartite_matching(pattern, perm_type="column")
    row_of_col = np.full(n, -1)
    for r, c in enumerate(col_of_row):
        if c >= 0:
            row_of_col[c] = r
    by_col = pattern.T.tocsr()
    h_cols, h_rows = _reach([c for c in range(n) if row_of_col[c] < 0], by_col, col_of_row)
    v_rows, v_cols = _reach([r for r in range(m) if col_of_row[r] < 0], pattern, row_of_col)
    s_cols = [c for c in range(n) if c not in h_cols and c not in v_cols]
    index = {c: i for i, c in enumerate(s_cols)}
    edges = [
        (index[c], index[int(w)])
        for c in s_cols
        for w in pattern.indices[pattern.indptr[row_of_col[c]] : pattern.indptr[row_of_col[c] + 1]]
        if int(w) in index and int(w) != c
    ]
    k = len(s_cols)
    digraph = sp.csr_matrix((np.ones(len(edges)), ([e[0] for e in edges], [e[1] for e in edges])), shape=(k, k))
    count, labels = connected_components(digraph, directed=True, connection="strong")
    needs: list[set[int]] = [set() for _ in range(count)]
    for a, b in edges:
        if labels[a] != labels[b]:
            needs[labels[a]].add(int(labels[b]))
    first_row = [min(row_of_col[s_cols[i]] for i in range(k) if labels[i] == p) for p in range(count)]
    order = _topological(needs, first_row)
    blocks = [("over", r, c) for r, c in _parts(sorted(v_rows), sorted(v_cols), pattern)]
    for p in order:
        cols = [s_cols[i] for i in range(k) if labels[i] == p]
        blocks.append(("determined", sorted(int(row_of_col[c]) for c in cols), cols))
    blocks += [("under", r, c) for r, c in _parts(sorted(h_rows), sorted(h_cols), pattern)]
    return blocks


def _topological(needs: list[set[int]], first_row: list[int]) -> list[int]:
    """Kahn's order of a DAG (node -> nodes it needs first); among the ready nodes the lowest first row."""
    order: list[int] = []
    done: set[int] = set()
    while len(order) < len(needs):
        ready = [p for p in range(len(needs)) if p not in done and needs[p] <= done]
        p = min(ready, key=lambda b: first_row[b])
        order.append(p)
        done.add(p)
    return order


def merge_by_body(
    blocks: list[tuple[str, list[int], list[int]]],
    rows: list[Row],
    pattern: sp.csr_matrix,
    joins: Sequence[tuple[int, int]] = (),
) -> list[tuple[str, list[int], list[int]]]:
    """Coarsen the square blocks to whole bodies: the finest block-triangular form in which no body's
    rows are split between two square blocks (its rows in the over- or under-determined parts stay
    there) and the bodies of each pair in ``joins`` share a block. Blocks sharing a body merge;
    blocks on a cycle of the merged order merge; repeat.

    Args:
        blocks: (kind, rows, cols) per block, as `block_triangular` gives them.
        rows: (body, component) of every row.
        pattern: the system's sparse pattern (rows x unknowns).
        joins: pairs of bodies that must share a block.

    Returns:
        The coarsened blocks, in solve order.
    """
    square = [i for i, b in enumerate(blocks) if b[0] == "determined"]
    owner = {c: i for i in square for c in blocks[i][2]}
    group = {i: i for i in square}

    def find(i: int) -> int:
        while group[i] != i:
            i = group[i]
        return i

    while True:
        by_body: dict[int, int] = {}
        for i in square:
            for r in blocks[i][1]:
                body = rows[r][0]
                if body in by_body and find(by_body[body]) != find(i):
                    group[find(i)] = find(by_body[body])
                by_body.setdefault(body, i)
        for a, b in joins:
            if a in by_body and b in by_body and find(by_body[a]) != find(by_body[b]):
                group[find(by_body[a])] = find(by_body[b])
        roots = sorted({find(i) for i in square})
        slot = {root: n for n, root in enumerate(roots)}
        edges = {
            (slot[find(i)], slot[find(owner[int(c)])])
            for i in square
            for r in blocks[i][1]
            for c in pattern.indices[pattern.indptr[r] : pattern.indptr[r + 1]]
            if int(c) in owner
        }
        graph = sp.csr_matrix(
            (np.ones(len(edges)), tuple(np.array(sorted(edges)).T.reshape(2, -1))), shape=(len(roots), len(roots))
        )
        count, labels = connected_components(graph, directed=True, connection="strong")
        if count == len(roots):
            break
        for a, b in edges:
            if labels[a] == labels[b]:
                group[find(roots[a])] = find(roots[b])
    members = {root: [i for i in square if find(i) == root] for root in roots}
    merged = [
        (
            "determined",
            sorted(r for i in members[root] for r in blocks[i][1]),
            sorted(c for i in members[root] for c in blocks[i][2]),
        )
        for root in roots
    ]
    needs = [{b for a, b in edges if a == n and b != n} for n in range(len(roots))]
    order = _topological(needs, [min(block[1]) for block in merged])
    return [b for b in blocks if b[0] == "over"] + [merged[n] for n in order] + [b for b in blocks if b[0] == "under"]


LEVELS = ("skc", "body", "component")


def decompose(structure: Structure, home: Instant, level: str = "skc") -> list[SKC]:
    """The ordered SKCs of a mechanism from its structure and its home assembly.

    Args:
        structure: the structure graph.
        home: the home assembly's instant.
        level: "component": the finest Dulmage-Mendelsohn blocks; "body": coarsened to whole bodies
            (`merge_by_body`), where a driving link whose effort its own equilibrium fixes is a block of its own;
            "skc": also each driving link (the child of an actuated tree joint) joined to the bodies it carries,
            as Yang's ordered SOCs count the driving pair in the SOC it drives.

    Returns:
        The SKCs in solve order.

    Raises:
        InvalidParameters: unknown level.
    """
    if level not in LEVELS:
        raise InvalidParameters("level", level, f"expected one of {LEVELS}")
    rows, cols, pattern = equilibrium_matrix(structure, home, generic=True)
    _, _, numeric = equilibrium_matrix(structure, home, generic=False)
    sparse = sp.csr_matrix(pattern)
    blocks = block_triangular(sparse)
    if level != "component":
        joins = [
            (j.child, b)
            for j in structure.joints
            if j.actuated and level == "skc"
            for b, parent in structure.parents.items()
            if parent == j.child
        ]
        blocks = merge_by_body(blocks, rows, sparse, joins)
    skcs = []
    order = [j.name for j in structure.joints]
    for kind, r, c in blocks:
        block_rows = tuple(rows[i] for i in r)
        block_cols = tuple(cols[j] for j in c)
        body_ids = sorted({b for b, _ in block_rows})
        solved = sorted({name for name, k in block_cols if k >= 0}, key=order.index)
        released = tuple(
            n
            for n in solved
            if any(b != 0 and b not in body_ids for b in (structure.joint(n).parent, structure.joint(n).child))
        )
        rank = int(np.linalg.matrix_rank(numeric[np.ix_(r, c)])) if r and c else 0
        skcs.append(
            SKC(
                kind,
                block_rows,
                block_cols,
                tuple(structure.bodies[b] for b in body_ids),
                tuple(solved),
                released,
                tuple(name for name, k in block_cols if k < 0),
                rank,
            )
        )
    return skcs
