"""Readers for CalculiX result files: ``.frd`` (nodal results, ASCII) and ``.dat`` (printed
node/element output and eigenvalues).

.frd (CalculiX GraphiX manual, "Result Format"): a file of blocks, each ended by a line " -3"
(FINDINGS pitfall 9: split on "\\n -3", never on "-3", which also occurs inside numbers).
Block "    2C": node coordinates; block "  100C": one result set, with
" -4  NAME  ncomps  ..." (the set's name), " -5  COMPNAME ..." (one per component) and
" -1" value lines in fixed columns: the node number (I10 in the "long" ASCII format that ccx
writes, FORMAT = 1 in the block header; I5 in the short one), then values 12 characters wide
(E12.5, so neighbouring values can touch: "1.00000E+00-2.00000E+00"); a " -2" line continues
the previous node's values. Binary results (FORMAT = 2) raise ``ValueError``. The nodes
block "2C" is read in the long format (I10 node numbers), which is what ccx writes.

.dat: sections start with a title line such as " displacements (vx,vy,vz) for set NREF and
time  0.1000000E+01" or " stresses (elem, integ.pnt.,sxx,syy,szz,sxy,sxz,syz) for set EPRINT
and time ..."; the rows follow. The component names come from the title (ccx prints the shear
stresses in the order xy, xz, yz there, but xy, yz, zx in the .frd). The eigenvalue table
follows "E I G E N V A L U E   O U T P U T".
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np


@dataclass(frozen=True, eq=False)
class FrdResult:
    name: str                      # e.g. "DISP", "STRESS"
    components: tuple[str, ...]    # e.g. ("D1", "D2", "D3") (ALL entries dropped)
    nodes: np.ndarray              # (n,) node ids as in the file
    values: np.ndarray             # (n, ncomp)
    step: int
    time: float


@dataclass(frozen=True, eq=False)
class Frd:
    node_ids: np.ndarray
    coords: np.ndarray             # (n, 3)
    results: tuple[FrdResult, ...] = field(default_factory=tuple)

    def result(self, name: str, step: int | None = None) -> FrdResult:
        for r in self.results:
            if r.name == name and (step is None or r.step == step):
                return r
        raise KeyError(f"no result {name!r} in the .frd file")


def _values(line: str, start: int) -> list[float]:
    s = line[start:].rstrip("\n")
    return [float(s[i:i + 12]) for i in range(0, len(s.rstrip()), 12)]


def parse_frd(text: str) -> Frd:
    blocks = text.split("\n -3")
    node_ids = np.zeros(0, dtype=np.int64)
    coords = np.zeros((0, 3))
    results = []
    for blk in blocks:
        lines = [ln for ln in blk.split("\n") if ln.strip()]
        if not lines:
            continue
        head = None
        for i, ln in enumerate(lines):
            if ln.lstrip().startswith(("2C", "3C", "100C")) or ln[:6].strip() in ("2C", "3C") \
                    or re.match(r"^\s*(2|3|100)C", ln):
                head = i
                break
        if head is None:
            continue
        key = lines[head].split()[0]
        if key.startswith("2C"):
            ids, xyz = [], []
            # (1X,'   2','C',18X,I12,37X,I1): node count, FORMAT (0 short, 1 long)
            wid = 5 if lines[head].split()[-1] == "0" else 10
            for ln in lines[head + 1:]:
                if ln.startswith(" -1"):
                    ids.append(int(ln[3:3 + wid]))
                    xyz.append(_values(ln, 3 + wid)[:3])
            node_ids = np.array(ids, dtype=np.int64)
            coords = np.array(xyz, dtype=float).reshape(-1, 3)
        elif key.startswith("100C"):
            hdr = lines[head]
            # (1X,' 100','C',6A1,E12.5,I12,20A1,I2,I5,10A1,I2): value, nodes, text, type,
            # step number, analysis, FORMAT (0 ASCII short: I5 nodes, 1 ASCII long: I10
            # nodes, 2 binary)
            fmt = hdr[73:75].strip() or "0"
            if fmt not in ("0", "1"):
                raise ValueError(f"binary .frd results are not read (format {fmt!r})")
            wid = 10 if fmt == "1" else 5
            try:
                t = float(hdr[12:24])
            except ValueError:
                t = float("nan")
            try:
                step = int(hdr[58:63])
            except ValueError:
                step = 0
            name, comps, ids, vals = "", [], [], []
            for ln in lines[head + 1:]:
                tag = ln[:3]
                if tag == " -4":
                    name = ln.split()[1]
                elif tag == " -5":
                    parts = ln.split()
                    # an "ALL" pseudo-component (vector magnitude) has no values of its own
                    if parts[1] != "ALL":
                        comps.append(parts[1])
                elif tag == " -1":
                    ids.append(int(ln[3:3 + wid]))
                    vals.append(_values(ln, 3 + wid))
                elif tag == " -2":
                    vals[-1].extend(_values(ln, 3 + wid))
            nc = len(comps)
            arr = np.array([v[:nc] for v in vals], dtype=float).reshape(-1, nc)
            results.append(FrdResult(name, tuple(comps), np.array(ids, dtype=np.int64), arr,
                                     step, t))
    return Frd(node_ids, coords, tuple(results))


def read_frd(path) -> Frd:
    return parse_frd(Path(path).read_text(errors="replace"))


# --------------------------------------------------------------------------- .dat

@dataclass(frozen=True, eq=False)
class DatTable:
    title: str                     # "displacements", "forces", "stresses", ...
    set_name: str
    columns: tuple[str, ...]       # names from the title, e.g. ("vx", "vy", "vz")
    keys: np.ndarray               # (n, k): node (k = 1), element and integration point (k = 2)
                                   # or nothing (k = 0: a TOTALS row)
    values: np.ndarray             # (n, len(columns) - k)
    time: float


@dataclass(frozen=True, eq=False)
class Dat:
    tables: tuple[DatTable, ...]
    eigenvalues: np.ndarray        # (n, 4): eigenvalue, ω rad/time, f cycles/time, imag part

    def table(self, title: str, set_name: str) -> DatTable:
        for t in self.tables:
            if t.title == title and t.set_name.upper() == set_name.upper():
                return t
        raise KeyError(f"no {title!r} table for set {set_name!r} in the .dat file")

    @property
    def frequencies_hz(self) -> np.ndarray:
        return self.eigenvalues[:, 2] if self.eigenvalues.size else np.zeros(0)


_TITLE = re.compile(r"^\s*([a-z][a-z .]*?)\s*\(([^)]*)\)\s*for set\s+(\S+)\s+and time\s+(\S+)")


def parse_dat(text: str) -> Dat:
    lines = text.split("\n")
    tables = []
    eig = []
    i = 0
    while i < len(lines):
        ln = lines[i]
        m = _TITLE.match(ln)
        if m:
            title, cols, set_name, t = m.groups()
            cols = tuple(c.strip() for c in cols.split(",") if c.strip())
            if title.startswith("total"):
                nkey = 0                   # TOTALS=ONLY: one row of sums, no key
            elif title.startswith("stresses") or "integ" in ",".join(cols):
                nkey = 2
            else:
                nkey = 1
            if nkey == 2:
                cols = tuple(c for c in cols if not c.startswith(("elem", "integ")))
                cols = ("elem", "integ.pnt.", *cols)
            elif nkey == 1:
                cols = ("node", *cols)
            keys, vals = [], []
            i += 1
            while i < len(lines) and not lines[i].strip():
                i += 1
            while i < len(lines) and lines[i].strip():
                parts = lines[i].split()
                try:
                    k = [int(p) for p in parts[:nkey]]
                    v = [float(p) for p in parts[nkey:]]
                except ValueError:
                    break
                keys.append(k)
                vals.append(v)
                i += 1
            nv = len(cols) - nkey
            tables.append(DatTable(title.strip(), set_name,
                                   cols, np.array(keys, dtype=np.int64).reshape(len(keys), nkey),
                                   np.array([v[:nv] for v in vals], dtype=float).reshape(-1, nv),
                                   float(t)))
            continue
        if "E I G E N V A L U E   O U T P U T" in ln:
            i += 1
            while i < len(lines):
                parts = lines[i].split()
                if parts and ("P A R T" in lines[i] or _TITLE.match(lines[i])
                              or "E I G E N" in lines[i]):
                    break
                if len(parts) == 5:
                    try:
                        int(parts[0])
                        eig.append([float(p) for p in parts[1:]])
                    except ValueError:
                        pass
                i += 1
            continue
        i += 1
    return Dat(tuple(tables), np.array(eig, dtype=float).reshape(-1, 4))


def read_dat(path) -> Dat:
    return parse_dat(Path(path).read_text(errors="replace"))
