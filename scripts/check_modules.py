#!/usr/bin/python3
"""The module rule: every include goes down the declared table, and no modules include each other.

A module is a directory: include/specula/<module>/ (its public headers) together with
src/<module>/ (its sources and private headers). A header directly in include/specula/ is a
module of its own named after its stem (include/specula/exceptions.h is module `exceptions`),
apps/<name>/ is module `apps/<name>` (apps/specula is the CLI), and python/ is module `python`
(the binding of `import specula`).

cmake/modules.txt declares, one line per module, what it may include:

    module: module module ...

A module may include the modules on its line and, through them, every module they may include:
the modules declared below it. This script reads every #include of every .h, .cpp and .inl under
include/specula/, src/, apps/ and python/, resolves it to a module (a quoted include first against the
including file's directory, then against include/ and the tree's root; an include that names no
file of the tree is a library's and is skipped), and fails, one line per violation, on

  - an include of a module not declared below the including module,
  - a module with files, or an included module, that cmake/modules.txt does not declare,
  - a cycle in cmake/modules.txt, and a cycle among the modules the includes actually connect.

    /usr/bin/python3 scripts/check_modules.py [--root DIR] [--graph]

--root checks another tree (with its own cmake/modules.txt); --graph first prints every
module-to-module edge with the number of includes behind it and the first of them.
Exit status 0: no violation; 1: some. Standard library only.
"""
import argparse
import re
import sys
from collections import defaultdict
from dataclasses import dataclass
from pathlib import Path

TABLE = Path("cmake/modules.txt")
SCANNED_DIRS = ("include/specula", "src", "apps", "python")
SOURCE_SUFFIXES = {".h", ".cpp", ".inl"}
INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]')


@dataclass(frozen=True)
class Include:
    """One #include line that names a file of another module of the tree."""
    path: str  # the including file, relative to the root
    line: int
    text: str  # as written: "specula/lobes/lobe.h" or <specula/lobes/lobe.h>
    source: str  # the including file's module
    target: str  # the included file's module

    def where(self):
        return f"{self.path}:{self.line}: #include {self.text}"


def read_table(root):
    """The declared table, {module: [modules on its line]}, and the problems of the table itself."""
    declared, problems = {}, []
    for number, raw in enumerate((root / TABLE).read_text().splitlines(), start=1):
        line = raw.split("#", 1)[0].strip()
        if not line:
            continue
        module, colon, dependencies = line.partition(":")
        module = module.strip()
        if not colon or not module:
            problems.append(f"{TABLE}:{number}: expected 'module: modules it may include', got '{raw}'")
        elif module in declared:
            problems.append(f"{TABLE}:{number}: module {module} is declared twice")
        else:
            declared[module] = dependencies.replace(",", " ").split()
    for module, dependencies in declared.items():
        problems += [f"{TABLE}: {module} lists {dependency}, which is not declared"
                     for dependency in dependencies if dependency not in declared]
    return declared, problems


def below(declared):
    """{module: every module declared below it}: the transitive closure of the table."""
    closure = {}

    def reach(module, visiting):
        if module not in closure:
            if module in visiting:  # a declared cycle, which declared_cycles reports
                return set()
            found = set()
            for dependency in declared.get(module, []):
                found |= {dependency} | reach(dependency, visiting | {module})
            closure[module] = found
        return closure[module]

    for module in declared:
        reach(module, frozenset())
    return closure


def module_of(root, file):
    """The module a file of the tree belongs to, or None for a file outside the scanned folders."""
    parts = file.relative_to(root).parts
    if parts[:2] == ("include", "specula") and len(parts) > 2:
        return parts[2] if len(parts) > 3 else Path(parts[2]).stem
    if parts[0] == "src" and len(parts) > 2:
        return parts[1]
    if parts[0] == "apps" and len(parts) > 2:
        return f"apps/{parts[1]}"
    if parts[0] == "python" and len(parts) > 1:
        return "python"
    return None


def resolve(root, file, quote, name):
    """The file of the tree that an include names, or None for a library's header."""
    bases = ([file.parent] if quote == '"' else []) + [root / "include", root]
    for base in bases:
        candidate = (base / name).resolve()
        if candidate.is_file() and candidate.is_relative_to(root):
            return candidate
    return None


def source_files(root):
    for folder in SCANNED_DIRS:
        yield from sorted(f for f in (root / folder).rglob("*") if f.suffix in SOURCE_SUFFIXES)


def includes_of(root, file):
    """The includes of `file` that name a file of another module."""
    source = module_of(root, file)
    for number, line in enumerate(file.read_text(errors="replace").splitlines(), start=1):
        match = INCLUDE.match(line)
        if not match:
            continue
        quote, name = match.groups()
        included = resolve(root, file, quote, name)
        target = included and module_of(root, included)
        if target and target != source:
            text = f'"{name}"' if quote == '"' else f"<{name}>"
            yield Include(str(file.relative_to(root)), number, text, source, target)


def scan(root):
    """Every module with files ({module: its first file}) and every include across modules."""
    modules, includes = {}, []
    for file in source_files(root):
        modules.setdefault(module_of(root, file), str(file.relative_to(root)))
        includes += includes_of(root, file)
    return modules, includes


def undeclared(modules, includes, declared):
    """One line per module with files that the table lacks, and one per include of such a module."""
    return ([f"{first_file}: module {module} is not declared in {TABLE}"
             for module, first_file in sorted(modules.items()) if module not in declared]
            + [f"{include.where()}: {include.source} includes {include.target}, "
               f"which {TABLE} does not declare"
               for include in includes if include.source in declared and include.target not in declared])


def forbidden(include, declared, closure):
    """Whether `include`, between declared modules, goes to one not declared below its own."""
    source, target = include.source, include.target
    return source in declared and target in declared and target not in closure[source]


def forbidden_includes(includes, declared, closure):
    """One line per include of a module not declared below the including module."""
    lines = []
    for include in (i for i in includes if forbidden(i, declared, closure)):
        source, target = include.source, include.target
        why = (f"{target} is declared above {source}" if source in closure[target]
               else f"{target} is not declared below {source}")
        lines.append(f"{include.where()}: {source} may not include {target} ({why})")
    return lines


def strongly_connected(graph):
    """The strongly connected components of {node: set of nodes} with more than one node (Tarjan)."""
    index, low, stack, on_stack, components = {}, {}, [], set(), []

    def visit(node):
        index[node] = low[node] = len(index)
        stack.append(node)
        on_stack.add(node)
        for successor in sorted(graph.get(node, ())):
            if successor not in index:
                visit(successor)
                low[node] = min(low[node], low[successor])
            elif successor in on_stack:
                low[node] = min(low[node], index[successor])
        if low[node] == index[node]:
            component = set()
            while node not in component:
                component.add(stack.pop())
            on_stack.difference_update(component)
            if len(component) > 1:
                components.append(component)

    for node in sorted(graph):
        if node not in index:
            visit(node)
    return components


def shortest_cycle(graph, component):
    """A shortest cycle through the first module of `component`: [start, ..., start]."""
    start = min(component)
    paths, frontier = {start: [start]}, [start]
    while frontier:
        following = []
        for node in frontier:
            for successor in sorted(graph[node] & component):
                if successor == start:
                    return paths[node] + [start]
                if successor not in paths:
                    paths[successor] = paths[node] + [successor]
                    following.append(successor)
        frontier = following
    raise AssertionError("a strongly connected component has a cycle through each of its nodes")


def cycles(graph, describe_edge):
    """One line per strongly connected component: a shortest cycle in it, each edge described."""
    lines = []
    for component in strongly_connected(graph):
        cycle = shortest_cycle(graph, component)
        edges = "; ".join(describe_edge(a, b) for a, b in zip(cycle, cycle[1:]))
        lines.append(f"{' -> '.join(cycle)} ({edges}; modules in the cycle: {', '.join(sorted(component))})")
    return lines


def actual_graph(includes):
    """{source: {target: [its includes]}}: the modules the includes connect."""
    graph = defaultdict(lambda: defaultdict(list))
    for include in includes:
        graph[include.source][include.target].append(include)
    return graph


def cycle_violations(declared, graph):
    declared_graph = {module: set(dependencies) for module, dependencies in declared.items()}
    include_graph = {source: set(targets) for source, targets in graph.items()}
    return ([f"{TABLE}: declared cycle: {line}"
             for line in cycles(declared_graph, lambda a, b: f"{a} lists {b}")]
            + [f"include cycle: {line}"
               for line in cycles(include_graph, lambda a, b: graph[a][b][0].where())])


def print_graph(graph, is_forbidden):
    for source in sorted(graph):
        for target, includes in sorted(graph[source].items()):
            flag = "  [not declared]" if is_forbidden(includes[0]) else ""
            print(f"{source} -> {target}: includes {len(includes)}, first {includes[0].where()}{flag}")


def plural(count, noun):
    return f"{count} {noun}{'' if count == 1 else 's'}"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--root", type=Path, default=Path(__file__).resolve().parent.parent,
                        help="the tree to check (default: this repository)")
    parser.add_argument("--graph", action="store_true", help="print every module-to-module edge")
    arguments = parser.parse_args()
    root = arguments.root.resolve()
    if not (root / TABLE).is_file():
        parser.error(f"{root / TABLE} not found: --root must be a tree with its table of modules")

    declared, problems = read_table(root)
    closure = below(declared)
    modules, includes = scan(root)
    graph = actual_graph(includes)
    problems += (undeclared(modules, includes, declared)
                 + forbidden_includes(includes, declared, closure)
                 + cycle_violations(declared, graph))

    if arguments.graph:
        print_graph(graph, lambda include: forbidden(include, declared, closure))
    for problem in problems:
        print(problem)
    edges = sum(len(targets) for targets in graph.values())
    print(f"{root}: {plural(len(modules), 'module')}, {plural(edges, 'module edge')} "
          f"({plural(len(includes), 'include')} across modules): "
          f"{plural(len(problems), 'violation')} of {TABLE}")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
