"""Grammar-based random RS274/NGC programs in the dialect tnvctl supports
(docs/gcode.md), for differential testing against LinuxCNC's rs274: moves
in every plane and unit, centre and R arcs, helices and full circles,
dwells, spindle, coolant, tools and length offsets, work offsets, G10,
G92, G28/G30, G53, canned cycles (G73, G81-G89 in G17, G18 and G19),
cutter radius compensation (G41/G42/G41.1/G42.1
contours of lines and arcs, G40 and a straight exit), parameters,
expressions, comments and O-word control flow, and pallet changes (M60)
between statements, tool table edits (G10 L1/L10/L11, after the first tool
change) and inverse-time runs (G93 lines and full circles, then G94 F).
Every program is valid by construction; each seed gives one program.
The pallet changes, and the tool table edits and inverse-time runs, are
drawn from streams of their own (seeded from the seed), so a seed's program
is the one it gave before they were written, with their lines added.
"""
from __future__ import annotations

import math
import random

AXES = "XYZ"
PLANES = {17: ("X", "Y", "Z", "I", "J"), 18: ("Z", "X", "Y", "K", "I"), 19: ("Y", "Z", "X", "J", "K")}
FUNCTIONS = ["abs", "cos", "sin", "sqrt", "fix", "fup", "round", "exp", "tan"]


class Generator:
    def __init__(self, seed: int, tool_count: int = 20):
        self.r = random.Random(seed)
        self.pallet = random.Random(f"M60 {seed}")  # M60's own stream: the other draws stay as they were
        self.extra = random.Random(f"G10 L1 G93 {seed}")  # tool table edits and inverse time: a stream of their own too
        self.tool_changed = False  # a T M6 ran (rs274 takes the table's first tool as loaded until then)
        self.tool_count = tool_count
        self.lines: list[str] = []
        self.absolute = True
        self.inch = False
        self.plane = 17
        self.params: dict[str, float] = {}
        self.depth = 0
        self.length_offset = False  # G43 in force
        self.next_label = 100

    # -- values --------------------------------------------------------
    def num(self, lo: float, hi: float) -> str:
        return f"{self.r.uniform(lo, hi):.4f}".rstrip("0").rstrip(".") or "0"

    def scale(self) -> float:
        return 1.0 / 25.4 if self.inch else 1.0

    def value(self, lo: float, hi: float) -> str:
        """A coordinate: a number, a parameter, or an expression that evaluates into [lo, hi]."""
        r = self.r.random()
        v = self.r.uniform(lo, hi)
        if r < 0.6 or not self.params:
            return f"{v:.4f}"
        name = self.r.choice(sorted(self.params))
        p = self.params[name]
        if r < 0.75:
            return f"[{name}+{v - p:.4f}]"
        f = self.r.choice(["abs", "fix", "fup", "round", "sqrt"])
        inner = abs(p) if f == "sqrt" else p
        fv = {"abs": abs, "fix": math.floor, "fup": math.ceil, "sqrt": math.sqrt,
              "round": lambda x: float(int(x + (0.5 if x >= 0 else -0.5)))}[f](inner)
        arg = f"abs[{name}]" if f == "sqrt" else name
        return f"[{f}[{arg}]+{v - fv:.4f}]"

    def set_param(self) -> None:
        kind = self.r.random()
        if kind < 0.4:
            name = f"#{self.r.randint(100, 120)}"
        elif kind < 0.8:
            name = f"#<p{self.r.randint(0, 5)}>"
        else:
            name = f"#<_g{self.r.randint(0, 3)}>"
        a, b = self.r.uniform(-20, 20), self.r.uniform(0.5, 4)
        op = self.r.choice(["+", "-", "*", "/", "**"])
        if op == "**":
            b = float(self.r.randint(0, 3))
        val = {"+": lambda: a + b, "-": lambda: a - b, "*": lambda: a * b, "/": lambda: a / b,
               "**": lambda: a ** b}[op]()
        if abs(val) > 1e4:
            op, val = "+", a + b
        self.lines.append(f"{name}=[{a:.4f}{op}{b:.4f}]")
        self.params[name] = val

    # -- statements ----------------------------------------------------
    def move(self) -> None:
        g = self.r.choice(["G0", "G1", "G1", ""])
        axes = [a for a in AXES if self.r.random() < 0.6] or ["X"]
        span = 50.0 * self.scale()
        words = "".join(f"{a}{self.value(-span, span)}" for a in axes)
        f = f" F{self.num(50, 2000)}" if g == "G1" and self.r.random() < 0.3 else ""
        self.lines.append(f"{g or 'G1'} {words}{f}")

    def arc(self) -> None:
        first, second, axis, l1, l2 = PLANES[self.plane]
        s = self.scale()
        g = self.r.choice(["G2", "G3"])
        helix = f" {axis}{self.num(-5 * s, 5 * s)}" if self.r.random() < 0.3 else ""
        prefix = "G91 " if self.absolute else ""
        suffix = "\nG90" if self.absolute else ""
        if self.r.random() < 0.35:  # R form
            d1, d2 = self.r.uniform(-20, 20) * s, self.r.uniform(-20, 20) * s
            chord = math.hypot(d1, d2)
            if chord < 0.5 * s:
                d1 += s
                chord = math.hypot(d1, d2)
            radius = chord / 2 + self.r.uniform(0.01, 20) * s
            sign = "-" if self.r.random() < 0.3 else ""
            helix = f" {axis}{self.num(-5 * s, 5 * s)}" if self.r.random() < 0.3 else ""
            self.lines.append(f"{prefix}{g} {first}{d1:.4f} {second}{d2:.4f}{helix} R{sign}{radius:.4f}{suffix}")
            return
        i, j = self.r.uniform(-15, 15) * s, self.r.uniform(-15, 15) * s
        if math.hypot(i, j) < 1.0 * s:
            i += 2 * s
        i, j = round(i, 4), round(j, 4)
        radius = math.hypot(i, j)
        a0 = math.atan2(-j, -i)
        full = self.r.random() < 0.15
        a1 = a0 if full else self.r.uniform(-math.pi, math.pi)
        e1, e2 = i + radius * math.cos(a1), j + radius * math.sin(a1)
        if full:
            e1, e2 = 0.0, 0.0
        turns = f" P{self.r.randint(1, 3)}" if self.r.random() < 0.15 else ""
        self.lines.append(f"{prefix}{g} {first}{e1:.4f} {second}{e2:.4f}{helix} {l1}{i:.4f} {l2}{j:.4f}{turns}{suffix}")

    def modal(self) -> None:
        c = self.r.randrange(16)
        if c == 0:
            self.plane = self.r.choice([17, 18, 19])
            self.lines.append(f"G{self.plane}")
        elif c == 1 and not self.length_offset:
            # LinuxCNC does not convert a tool length offset at G20/G21 (a
            # deliberate deviation, docs/gcode.md): units change only without one.
            self.inch = not self.inch
            self.lines.append("G20" if self.inch else "G21")
        elif c == 2:
            self.absolute = not self.absolute
            self.lines.append("G90" if self.absolute else "G91")
        elif c == 3:
            self.lines.append(f"G4 P{self.num(0, 2)}")
        elif c == 4:
            self.lines.append(f"S{self.r.randint(0, 12000)} M{self.r.choice([3, 4, 5])}")
        elif c == 5:
            self.lines.append(f"M{self.r.choice([7, 8, 9])}")
        elif c == 6:
            t = self.r.randint(1, self.tool_count)
            self.lines.append(f"T{t} M6")
            self.tool_changed = True
            offset = self.r.choice(["G43", f"G43 H{self.r.randint(1, self.tool_count)}", "G49"])
            self.length_offset = offset != "G49"
            self.lines.append(offset)
        elif c == 7:
            self.lines.append(self.r.choice(["G54", "G55", "G56", "G57", "G58", "G59", "G59.1", "G59.2", "G59.3"]))
        elif c == 8:
            axes = "".join(f"{a}{self.num(-30, 30)}" for a in AXES if self.r.random() < 0.6) or "X1"
            self.lines.append(f"G10 L{self.r.choice([2, 20])} P{self.r.randint(0, 9)} {axes}")
        elif c == 9:
            axes = "".join(f"{a}{self.num(-30, 30)}" for a in AXES if self.r.random() < 0.6) or "Z0"
            self.lines.append(self.r.choice([f"G92 {axes}", "G92.1", "G92.2", "G92.3"]))
        elif c == 10:
            kind = self.r.choice(["G28", "G30", "G28.1", "G30.1"])
            via = "".join(f"{a}{self.num(-20, 20)}" for a in AXES if self.r.random() < 0.4)
            if kind.endswith(".1"):
                via = ""
            self.lines.append(f"{kind} {via}".strip() if self.absolute or not via else f"G90 {kind} {via}\nG91")
        elif c == 11:
            if self.absolute:
                self.lines.append(f"G53 G{self.r.choice([0, 1])} X{self.num(-40, 40)} Y{self.num(-40, 40)}")
        elif c == 12:
            self.lines.append(self.r.choice(["G61", "G61.1", f"G64 P{self.num(0, 0.5)}", f"G64 P{self.num(0, 0.5)} Q{self.num(0, 0.5)}", "G64"]))
        elif c == 13:
            self.lines.append(f"F{self.num(10, 3000)}")
        elif c == 14:
            self.lines.append(self.r.choice(["(a comment)", "(MSG, a message)", "G1 X1 (moving) ; and a tail"]))
        else:
            self.lines.append("G94")
            self.lines.append(f"F{self.num(10, 3000)}")

    def xy_move(self) -> None:
        g = self.r.choice(["G1", "G1", "G1", "G0"])
        span = 50.0 * self.scale()
        z = f" Z{self.value(-5 * self.scale(), 5 * self.scale())}" if self.r.random() < 0.15 else ""
        self.lines.append(f"{g} X{self.value(-span, span)} Y{self.value(-span, span)}{z}")

    def compensated_contour(self) -> None:
        """G41/G42 (a tool's D, the tool in the spindle, or G41.1/G42.1 with a
        diameter), an entry move, lines and arcs in XY, then G40 and the
        straight exit move. Only what LinuxCNC allows while compensating
        runs in between (no offsets, tools, planes or path modes); a contour
        the tool cannot follow without gouging is refused by both."""
        if self.plane != 17:
            self.plane = 17
            self.lines.append("G17")
        s = self.scale()
        side = self.r.choice(["G41", "G42"])
        kind = self.r.random()
        if kind < 0.6:
            self.lines.append(f"{side} D{self.r.randint(0, 3)}")
        elif kind < 0.75:
            self.lines.append(side)
        else:
            sign = "-" if self.r.random() < 0.2 else ""
            self.lines.append(f"{side}.1 D{sign}{self.num(0.2 * s, 4 * s)}")
        self.arc() if self.r.random() < 0.2 else self.xy_move()  # the entry move
        for _ in range(self.r.randint(1, 6)):
            r = self.r.random()
            if r < 0.45:
                self.xy_move()
            elif r < 0.8:
                self.arc()
            elif r < 0.85:
                self.lines.append(f"F{self.num(10, 3000)}")
            elif r < 0.9:
                self.lines.append(self.r.choice(["(a comment)", "(MSG, a message)", "G4 P0.5", "M8", "M9",
                                                 f"S{self.r.randint(0, 12000)} M3"]))
            else:
                self.absolute = not self.absolute
                self.lines.append("G90" if self.absolute else "G91")
        self.lines.append("G40")
        self.xy_move()  # the exit move: straight

    def cycle(self) -> None:
        """A run of canned cycles (in the plane in force, G90 or G91), ended by G80."""
        word_a, word_b, word_c = PLANES[self.plane][:3]  # the hole on a, b; the tool along c
        s = self.scale()
        r = self.r.uniform(-5, 10) * s
        depth = self.r.uniform(0.5, 15) * s
        bottom = r - depth
        if not self.absolute:  # G91: R from the start, the bottom from R
            bottom = bottom - r
        codes = ["G81", "G82", "G83", "G73", "G84", "G85", "G86", "G87", "G88", "G89"]
        if self.plane != 17:  # rs274 taps along permuted axes outside G17; tnvctl refuses G84 there
            codes.remove("G84")
        code = self.r.choice(codes)
        offset = {"X": "I", "Y": "J", "Z": "K"}  # G87's offset words, by axis
        top = self.r.uniform(0.1, 0.9) * depth  # G87's top of the back bore: above the bottom
        extra = {"G81": "", "G82": f" P{self.num(0, 1)}", "G83": f" Q{self.r.uniform(0.3, 4) * s:.4f}",
                 "G73": f" Q{self.r.uniform(0.3, 4) * s:.4f}", "G85": "", "G86": f" P{self.num(0, 1)}",
                 "G87": (f" {offset[word_a]}{self.r.uniform(-3, 3) * s:.4f} {offset[word_b]}{self.r.uniform(-3, 3) * s:.4f}"
                         f" {offset[word_c]}{(top if not self.absolute else r - depth + top):.4f}"),
                 "G88": f" P{self.num(0, 1)}", "G89": f" P{self.num(0, 1)}",
                 "G84": self.r.choice(["", f" P{self.num(0, 1)}"])}[code]
        if code == "G84":  # tapping needs the spindle clockwise
            self.lines.append(f"S{self.r.randint(100, 3000)} M3")
        elif code in ("G86", "G87", "G88"):  # these stop and restart the spindle: it must turn
            self.lines.append(f"S{self.r.randint(100, 3000)} {self.r.choice(['M3', 'M4'])}")
        repeat = f" L{self.r.randint(1, 3)}" if self.r.random() < 0.2 else ""
        retract = self.r.choice(["G98 ", "G99 ", ""])
        span = 40.0 * s
        self.lines.append(f"{retract}{code} {word_a}{self.value(-span, span)} {word_b}{self.value(-span, span)} "
                          f"{word_c}{bottom:.4f} R{r:.4f}{extra}{repeat}")
        for _ in range(self.r.randint(0, 2)):
            self.lines.append(f"{word_a}{self.value(-span, span)}" +
                              (f" {word_b}{self.num(-span, span)}" if self.r.random() < 0.5 else ""))
        self.lines.append("G80")

    def control(self) -> None:
        if self.depth >= 2:
            return self.move()
        self.depth += 1
        label = f"o{self.next_label}"  # LinuxCNC refuses a label that opens two blocks
        self.next_label += 1 + self.r.randint(0, 9)
        kind = self.r.randrange(3)
        if kind == 0:
            self.lines.append(f"{label} if [{self.r.choice(['1', '0', '#<_g0> gt 0', '2 lt 3'])} and 1]"
                              if "#<_g0>" in self.params else f"{label} if [{self.r.choice(['1', '0', '2 lt 3'])}]")
            self.body(2)
            if self.r.random() < 0.5:
                self.lines.append(f"{label} else")
                self.body(2)
            self.lines.append(f"{label} endif")
        elif kind == 1:
            counter = f"#<n{self.depth}>"
            self.lines.append(f"{counter}=0")
            self.lines.append(f"{label} while [{counter} lt {self.r.randint(0, 3)}]")
            self.body(2)
            self.lines.append(f"{counter}=[{counter}+1]")
            self.lines.append(f"{label} endwhile")
        else:
            self.lines.append(f"{label} repeat [{self.r.randint(0, 3)}]")
            self.body(2)
            self.lines.append(f"{label} endrepeat")
        self.depth -= 1

    def body(self, n: int) -> None:
        # Only moves and arcs: a branch not taken must leave the modal state
        # and the defined parameters as the generator believes them.
        for _ in range(self.r.randint(1, n)):
            if self.r.random() < 0.7:
                self.move()
            else:
                self.arc()

    def statement(self) -> None:
        r = self.r.random()
        if r < 0.35:
            self.move()
        elif r < 0.55:
            self.arc()
        elif r < 0.8:
            self.modal()
        elif r < 0.85:
            self.set_param()
        elif r < 0.9:
            self.cycle()
        elif r < 0.95:
            self.compensated_contour()
        else:
            self.control()

    def pallet_change(self) -> None:
        # M60: PALLET_SHUTTLE() then PROGRAM_STOP(), after the line's move when it has one.
        if self.pallet.random() >= 0.04:
            return
        p = self.pallet
        self.lines.append(p.choice(["M60", "M5 M60", f"G1 X{p.uniform(-5, 5):.4f} M60", f"G0 Y{p.uniform(-5, 5):.4f} M60"]))

    def tool_edit(self) -> None:
        # G10 L1 / L10 / L11 of a tool of the table, after the first tool change.
        e = self.extra
        if not self.tool_changed or e.random() >= 0.06:
            return
        s = self.scale()
        words = "".join(f" {a}{e.uniform(-20 * s, 20 * s):.4f}" for a in AXES if e.random() < 0.5)
        if e.random() < 0.4:
            words += f" R{e.uniform(0.1 * s, 3 * s):.4f}"
        if e.random() < 0.2:
            words += f" I{e.uniform(-90, 90):.2f} J{e.uniform(-90, 90):.2f}"
        if e.random() < 0.2:
            words += f" Q{e.randint(0, 9)}"
        self.lines.append(f"G10 L{e.choice([1, 1, 10, 11])} P{e.randint(1, self.tool_count)}{words or ' Z1'}")

    def inverse_time(self) -> None:
        # G93: feed moves each with their F, a full circle (a helix) in the
        # plane in force, a rapid between; then G94 and a feed rate again.
        e = self.extra
        if e.random() >= 0.04:
            return
        s = self.scale()
        first, second, normal, c1, c2 = PLANES[self.plane]
        self.lines.append("G93")
        for _ in range(e.randint(1, 3)):
            kind = e.random()
            if kind < 0.5:
                axes = "".join(f" {a}{e.uniform(-10 * s, 10 * s):.4f}" for a in AXES if e.random() < 0.6)
                self.lines.append(f"G1{axes} F{e.uniform(0.5, 20):.3f}")
            elif kind < 0.8:
                helix = f" {normal}{e.uniform(-3 * s, 3 * s):.4f}" if e.random() < 0.4 else ""
                self.lines.append(f"G{e.choice([2, 3])} {c1}{e.uniform(1 * s, 5 * s):.4f} {c2}0{helix} F{e.uniform(0.5, 10):.3f}")
            else:
                self.lines.append(f"G0 {first}{e.uniform(-10 * s, 10 * s):.4f} {second}{e.uniform(-10 * s, 10 * s):.4f}")
        # Ends in G1, as a feed move: a later bare X Y is a line again.
        self.lines.append(f"G1 {first}{e.uniform(-10 * s, 10 * s):.4f} F{e.uniform(0.5, 20):.3f}")
        self.lines.append(f"G94 F{e.uniform(100, 2000):.1f}")

    def program(self, statements: int) -> str:
        self.lines = ["(random program)", "G21 G17 G90 G94", f"F{self.num(100, 2000)}"]
        self.lines.append("o<sub1> sub")
        self.lines.append("G91 G1 X#1 Y#2\nG90")
        self.lines.append("o<sub1> endsub")
        for _ in range(statements):
            if self.r.random() < 0.05:
                self.lines.append(f"o<sub1> call [{self.num(-5, 5)}] [{self.num(-5, 5)}]")
                if not self.absolute:  # the subroutine ends in G90
                    self.lines.append("G91")
            self.statement()
            self.pallet_change()
            self.tool_edit()
            self.inverse_time()
        self.lines.append(self.r.choice(["M2", "M30"]))
        return "\n".join(self.lines) + "\n"


def random_program(seed: int, statements: int = 30) -> str:
    return Generator(seed).program(statements)


if __name__ == "__main__":
    import sys
    print(random_program(int(sys.argv[1]) if len(sys.argv) > 1 else 1), end="")
