#!/usr/bin/env python3
"""Update an estep parameter file written for estep 0.1 to the current entries.

    python3 scripts/update_prm.py old.prm > new.prm      (or --in-place old.prm ...)

The entries that moved (estep names them when it reads an old file): the energy-stepping and
time-step entries went into the integrators' own subsections, the material into the subsection
Material, the field output, H1 norm and progress entries into Postprocessors; the mesh type
'seed cube' is now called 'box'. Comments are kept
with the entry or subsection they precede; the layout is re-indented by two spaces per level.
"""
import argparse
import sys

DEFAULT_POSTPROCESSORS = ["history", "step histogram", "progress", "contact monitor"]
IMPLICIT_METHODS = {"ida bdf", "arkode midpoint", "arkode irk", "energy momentum"}
MOVED = {
    ("Time integration", "Energy step"): ("Time integration", "Energy stepping", "Energy step"),
    ("Time integration", "Terrace offset"): ("Time integration", "Energy stepping", "Terrace offset"),
    ("Elastic body", "Material", "Model"): ("Material", "Model"),
    ("Elastic body", "Material", "Lambda"): ("Material", "Neo-Hookean", "Lambda"),
    ("Elastic body", "Material", "Mu"): ("Material", "Neo-Hookean", "Mu"),
    ("Elastic body", "Material", "Density"): ("Material", "Density"),
    ("Colliding balls", "Lambda"): ("Material", "Neo-Hookean", "Lambda"),
    ("Colliding balls", "Mu"): ("Material", "Neo-Hookean", "Mu"),
    ("Colliding balls", "Density"): ("Material", "Density"),
    ("Output", "Field output format"): ("Postprocessors", "Field output", "Format"),
    ("Output", "Progress interval"): ("Postprocessors", "Progress", "Interval"),
}


class Section:
    def __init__(self, name, comments=()):
        self.name, self.comments, self.items = name, list(comments), []

    def child(self, name):
        for item in self.items:
            if isinstance(item, Section) and item.name == name:
                return item
        section = Section(name)
        self.insert(section)
        return section

    def insert(self, item):
        """Append @p item before the closing end of this section."""
        closed = self.items and isinstance(self.items[-1], list) and self.items[-1][0] == "#end"
        self.items.insert(len(self.items) - 1 if closed else len(self.items), item)

    def set(self, path, value, comments=()):
        section = self
        for name in path[:-1]:
            section = section.child(name)
        for item in section.items:
            if isinstance(item, list) and item[0] == path[-1]:
                item[1] = value
                return
        section.insert([path[-1], value, list(comments)])


def parse(lines):
    root, stack, comments = Section(""), [], []
    stack.append(root)
    for raw in lines:
        line = raw.strip()
        if not line or line.startswith("#"):
            comments.append(line)
            continue
        word, _, rest = line.partition(" ")
        keyword = word.lower()
        if keyword == "subsection":
            section = Section(rest.strip(), comments)
            stack[-1].items.append(section)
            stack.append(section)
        elif keyword == "end":
            stack[-1].items.append(["#end", None, comments])
            stack.pop()
        elif keyword == "set":
            name, _, value = rest.partition("=")
            stack[-1].items.append([name.strip(), value.strip(), comments])
        else:  # include lines and anything else, kept as they are
            stack[-1].items.append(["#raw", line, comments])
        comments = []
    root.items.append(["#end", None, comments])
    return root


def entries(section, path=()):
    for item in section.items:
        if isinstance(item, Section):
            yield from entries(item, path + (item.name,))
        elif not item[0].startswith("#"):
            yield path + (item[0],), item


def update(root):
    method = "energy stepping"
    for path, item in entries(root):
        if path == ("Time integration", "Method"):
            method = item[1]
    for path, item in entries(root):
        if path[-2:] == ("Mesh", "Type") and item[1] == "seed cube":
            item[1] = "box"
    postprocessors = list(DEFAULT_POSTPROCESSORS)
    moves = []
    for path, item in list(entries(root)):
        name, value, comments = item
        target = MOVED.get(path)
        if path[0] == "Implicit integrators":
            target = ("Time integration",) + path
        elif path == ("Time integration", "Time step"):
            if method == "explicit newmark":
                target = ("Time integration", "Explicit Newmark", "Time step")
            elif method in IMPLICIT_METHODS:
                target = ("Time integration", "Implicit integrators", "Time step")
            else:
                target = ()  # energy stepping has no time step
        elif path == ("Output", "Field output interval"):
            target = ()
            if float(value) > 0:
                postprocessors.append("field output")
                target = ("Postprocessors", "Field output", "Interval")
        elif path == ("Output", "H1 norm"):
            target = ()
            if value.lower() in ("true", "yes", "1"):
                postprocessors.append("h1 norm")
        elif path == ("Output", "Progress"):
            target = ()
            if value == "off":
                postprocessors.remove("progress")
            elif value == "on":
                target = ("Postprocessors", "Progress", "Mode")
                value = "terminal"
        if target is None:
            continue
        moves.append((path, target, value, comments))
    for path, target, value, comments in moves:
        remove(root, path)
        if target:
            root.set(target, value, comments)
    if postprocessors != DEFAULT_POSTPROCESSORS:
        root.set(("Postprocessors", "List"), ", ".join(postprocessors))
    prune(root)


def remove(section, path):
    if len(path) == 1:
        section.items = [i for i in section.items
                         if isinstance(i, Section) or i[0] != path[0]]
        return
    remove(section.child(path[0]), path[1:])


def prune(section):
    """Drop subsections left without entries."""
    kept = []
    for item in section.items:
        if isinstance(item, Section):
            prune(item)
            if any(not isinstance(i, list) or not i[0].startswith("#end") for i in item.items):
                kept.append(item)
        else:
            kept.append(item)
    section.items = kept


def write(section, out, depth=0):
    pad = "  " * depth
    width = max([len(i[0]) for i in section.items
                 if isinstance(i, list) and not i[0].startswith("#")] or [0])
    for item in section.items:
        if isinstance(item, Section):
            if depth == 0 and out and out[-1] and not item.comments:
                out.append("")
            out.extend(pad + c if c else "" for c in item.comments)
            out.append(f"{pad}subsection {item.name}")
            write(item, out, depth + 1)
            if not any(isinstance(i, list) and i[0] == "#end" for i in item.items):
                out.append(f"{pad}end")
        else:
            name, value, comments = item
            inner = pad if name != "#end" else "  " * max(depth - 1, 0)
            out.extend(inner + c if c else "" for c in comments)
            if name == "#end":
                if depth > 0:
                    out.append(f"{inner}end")
            elif name == "#raw":
                out.append(pad + value)
            else:
                out.append(f"{pad}set {name:<{width}} = {value}")


def convert(text):
    root = parse(text.splitlines())
    update(root)
    out = []
    write(root, out)
    while out and not out[-1]:
        out.pop()
    return "\n".join(out) + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("files", nargs="+")
    parser.add_argument("--in-place", action="store_true", help="rewrite the files")
    args = parser.parse_args()
    for name in args.files:
        with open(name) as f:
            text = convert(f.read())
        if args.in_place:
            with open(name, "w") as f:
                f.write(text)
        else:
            sys.stdout.write(text)


if __name__ == "__main__":
    main()
