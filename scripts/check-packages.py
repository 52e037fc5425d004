#!/usr/bin/python3
"""Checks that every file from outside the repository that luxel's build and tests read comes
from a Debian package that scripts/packages.txt installs.

    scripts/check-packages.py BUILD_DIR [--packages FILE] [--deps FILE] [--link FILE]
                              [--probe-tests REGEX] [--opened FILE] [--no-runtime]

What is checked, each as it really happened on this machine (so that a machine stocked with
packages installed by hand cannot hide a missing line):
  - the headers the compiler read: `ninja -t deps` in BUILD_DIR (or --deps FILE, same format);
  - the libraries on the link lines: LINK_LIBRARIES in BUILD_DIR/build.ninja (or --link FILE,
    one path or -lNAME a line), -lNAME resolved the way the compiler driver does;
  - what the built programs load: `ldd` of every executable in BUILD_DIR/bin;
  - what the tests run: the programs CMake found for them (CMakeCache.txt) and, with
    --probe-tests REGEX, every file that the ctest tests matching REGEX executed or opened,
    watched with `strace -f` (the Mesa drivers EGL and GLX load, xvfb-run's X server, Node.js
    and the glTF validator); --opened FILE reads such an strace log instead.
Each file is mapped to the Debian package that owns it (dpkg's file lists); that package must
lie in the install closure of scripts/packages.txt: the listed packages and everything they
depend on (Depends and Pre-Depends, recursively, no Recommends), plus Debian's essential set,
which every Debian machine has. A file that belongs to no package, or to a package outside the
closure, is reported with the line to add. Exit 0: all covered; 1: something missing; 2: bad
command line. Needs only dpkg's own database, so it works offline and without apt's lists.
"""

from __future__ import annotations

import argparse
import glob
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile
from dataclasses import dataclass, field

DPKG_INFO = "/var/lib/dpkg/info"

# Files no package owns because the system generates them at install time. Reading them is
# fine: every Debian machine has them once the package that generates them is installed.
GENERATED = (
    re.compile(r"^/etc/"),  # configuration, ld.so.cache, alternatives
    re.compile(r"^/var/"),  # caches and state
    re.compile(r"^/usr/lib/locale/locale-archive$"),
    re.compile(r"^/usr/lib/x86_64-linux-gnu/gconv/gconv-modules\.cache$"),
    re.compile(r"/__pycache__/"),
    re.compile(r"^/usr/share/mime/"),
    re.compile(r"^/usr/share/fonts/.*\.cache"),
    re.compile(r"/\.cache/mesa_shader_cache/"),  # Mesa's shader cache, written by the tests
    # Message translations: looked up when present, and nothing breaks without them.
    re.compile(r"^/usr/share/locale/"),
)

# What an strace log may show that is not a file a package could provide.
NOT_FILES = re.compile(r"^/(proc|sys|dev|run|tmp)(/|$)")


@dataclass
class Use:
    """One file read from outside the repository, and what read it."""

    path: str
    why: str


@dataclass
class Packages:
    """dpkg's view of the installed system: who owns which file, who depends on whom."""

    owner: dict[str, list[str]] = field(default_factory=dict)
    depends: dict[str, list[list[str]]] = field(default_factory=dict)
    providers: dict[str, list[str]] = field(default_factory=dict)
    essential: set[str] = field(default_factory=set)


def strip_arch(name: str) -> str:
    return name.split(":", 1)[0].strip()


def parse_relations(text: str) -> list[list[str]]:
    """'a (>= 1) | b:any, c' -> [['a', 'b'], ['c']]"""
    clauses = []
    for clause in text.split(","):
        names = [strip_arch(re.sub(r"\(.*?\)|\[.*?\]|<.*?>", "", alt)) for alt in clause.split("|")]
        names = [n for n in names if n]
        if names:
            clauses.append(names)
    return clauses


def load_packages() -> Packages:
    db = Packages()
    query = subprocess.run(
        ["dpkg-query", "-W", "-f=${Package}\t${db:Status-Status}\t${Essential}\t${Provides}\t"
         "${Depends}\t${Pre-Depends}\n"],
        check=True, capture_output=True, text=True).stdout
    for line in query.splitlines():
        package, status, essential, provides, depends, pre_depends = (line.split("\t") + [""] * 6)[:6]
        if status != "installed":
            continue
        db.depends[package] = parse_relations(depends) + parse_relations(pre_depends)
        if essential == "yes":
            db.essential.add(package)
        for virtual in parse_relations(provides):
            db.providers.setdefault(virtual[0], []).append(package)
    for listing in glob.glob(os.path.join(DPKG_INFO, "*.list")):
        package = strip_arch(os.path.basename(listing)[: -len(".list")])
        with open(listing, encoding="utf-8", errors="replace") as lines:
            for path in lines:
                db.owner.setdefault(path.rstrip("\n"), []).append(package)
    return db


def closure(db: Packages, roots: list[str]) -> set[str]:
    """Every installed package reached from `roots` by Depends/Pre-Depends. Of a clause's
    alternatives, every one that is installed counts: apt would have installed one of them."""
    seen: set[str] = set()
    stack = list(roots)
    while stack:
        name = stack.pop()
        candidates = [name] if name in db.depends else db.providers.get(name, [])
        for package in candidates:
            if package in seen:
                continue
            seen.add(package)
            for clause in db.depends.get(package, []):
                stack.extend(clause)
    return seen


def path_variants(path: str) -> list[str]:
    """Debian 12 merges /usr: a package may list /lib/x.so while the loader names
    /usr/lib/x.so, or a symbolic link's name while a tool prints its target."""
    variants = []
    for candidate in (os.path.normpath(path), os.path.realpath(path)):
        variants.append(candidate)
        for top in ("/lib", "/bin", "/sbin"):
            if candidate.startswith("/usr" + top + "/"):
                variants.append(candidate[len("/usr"):])
            elif candidate.startswith(top + "/"):
                variants.append("/usr" + candidate)
    # A file reached through a linked directory (/usr/lib/x86_64-linux-gnu/foo -> ...).
    directory = os.path.realpath(os.path.dirname(path))
    variants.append(os.path.join(directory, os.path.basename(path)))
    return list(dict.fromkeys(variants))


def owners(db: Packages, path: str) -> list[str]:
    for variant in path_variants(path):
        if variant in db.owner:
            return db.owner[variant]
    return []


def read_listed(packages_file: str) -> list[str]:
    names = []
    with open(packages_file, encoding="utf-8") as lines:
        for line in lines:
            line = line.split("#", 1)[0].strip()
            if line:
                names.append(line)
    return names


def run(command: list[str], cwd: str | None = None) -> str:
    return subprocess.run(command, cwd=cwd, check=True, capture_output=True, text=True).stdout


def headers_from_deps(text: str, why: str) -> list[Use]:
    # `ninja -t deps`: "target: #deps N, deps mtime ..." then one indented path a line.
    return [Use(line.strip(), why) for line in text.splitlines()
            if line.startswith("    ") and line.strip().startswith("/")]


def link_inputs(build_ninja: str) -> list[str]:
    found = []
    with open(build_ninja, encoding="utf-8", errors="replace") as lines:
        for line in lines:
            stripped = line.strip()
            if stripped.startswith("LINK_LIBRARIES = "):
                found.extend(shlex.split(stripped[len("LINK_LIBRARIES = "):]))
    return found


def resolve_link_items(items: list[str], compiler: str) -> list[Use]:
    uses = []
    for item in dict.fromkeys(items):
        if item.startswith("-l"):
            name = item[2:]
            for suffix in (".so", ".a"):
                resolved = run([compiler, f"-print-file-name=lib{name}{suffix}"]).strip()
                if os.path.isabs(resolved):
                    uses.append(Use(resolved, f"linked as {item}"))
                    break
        elif item.startswith("/"):
            uses.append(Use(item, "on a link line"))
    return uses


def ldd_libraries(executables: list[str]) -> list[Use]:
    uses = {}
    for executable in executables:
        try:
            output = run(["ldd", executable])
        except subprocess.CalledProcessError:
            continue  # not a dynamic executable (a script)
        for line in output.splitlines():
            match = re.search(r"=>\s+(/\S+)", line) or re.match(r"\s+(/\S+)\s+\(", line)
            if match:
                uses.setdefault(match.group(1), Use(match.group(1),
                                                    f"loaded by {os.path.basename(executable)}"))
    return list(uses.values())


def programs_from_cache(build_dir: str) -> list[Use]:
    """Programs CMake found for the build and the tests (glad, xvfb-run, node, ...)."""
    uses = []
    cache = os.path.join(build_dir, "CMakeCache.txt")
    with open(cache, encoding="utf-8", errors="replace") as lines:
        for line in lines:
            match = re.match(r"^(LUXEL_\w+):FILEPATH=(/.+)$", line.strip())
            if match and os.path.isfile(match.group(2)):
                uses.append(Use(match.group(2), f"found by CMake as {match.group(1)}"))
    return uses


def opened_from_strace(log_file: str) -> list[Use]:
    """Files an strace log shows executed or opened successfully."""
    uses = {}
    pattern = re.compile(r'(execve|openat|open)\((?:AT_FDCWD, )?"([^"]+)".*\)\s+=\s+(\d+)')
    with open(log_file, encoding="utf-8", errors="replace") as lines:
        for line in lines:
            match = pattern.search(line)
            if not match or not match.group(2).startswith("/"):
                continue
            path = match.group(2)
            if NOT_FILES.match(path) or os.path.isdir(path):
                continue
            verb = "run" if match.group(1) == "execve" else "opened"
            uses.setdefault(path, Use(path, f"{verb} by the tests"))
    return list(uses.values())


def probe_tests(build_dir: str, regex: str, log_file: str) -> None:
    """Runs the ctest tests matching `regex` under strace, writing what they open to log_file."""
    env = dict(os.environ, EGL_PLATFORM=os.environ.get("EGL_PLATFORM", "surfaceless"))
    command = ["strace", "-f", "-qq", "-e", "trace=execve,open,openat", "-o", log_file,
               "ctest", "--test-dir", build_dir, "-R", regex, "--output-on-failure"]
    result = subprocess.run(command, env=env, capture_output=True, text=True)
    if result.returncode != 0:
        sys.stdout.write(result.stdout[-4000:] + result.stderr[-4000:])
        raise SystemExit(f"check-packages: error: the probed tests failed: {' '.join(command)}")
    if "No tests were found" in result.stdout or "tests passed" not in result.stdout:
        raise SystemExit(f"check-packages: error: --probe-tests '{regex}' ran no test")


def inside(path: str, folders: list[str]) -> bool:
    real = os.path.realpath(path)
    return any(real == f or real.startswith(f + os.sep) for f in folders)


def check(uses: list[Use], db: Packages, listed: list[str], ignore: list[str],
          packages_file: str) -> int:
    not_installed = [name for name in listed
                     if name not in db.depends and name not in db.providers]
    if not_installed:
        print(f"{packages_file}: listed but not installed (run scripts/setup.sh first): "
              + ", ".join(not_installed))
        return 1
    allowed = closure(db, listed) | closure(db, sorted(db.essential))
    missing: dict[str, list[Use]] = {}
    unowned: list[Use] = []
    checked = 0
    for use in {u.path: u for u in reversed(uses)}.values():  # each file once, first reason
        if inside(use.path, ignore) or any(p.search(use.path) for p in GENERATED):
            continue
        checked += 1
        packages = owners(db, use.path)
        if not packages:
            unowned.append(use)
        elif not any(p in allowed for p in packages):
            missing.setdefault(packages[0], []).append(use)
    for package, package_uses in sorted(missing.items()):
        examples = package_uses[:3]
        print(f"missing package: {package} provides "
              + "; ".join(f"{u.path} ({u.why})" for u in examples)
              + (f" and {len(package_uses) - 3} more files" if len(package_uses) > 3 else ""))
        print(f"  add the line '{package}' to {packages_file}")
    for use in unowned[:20]:
        print(f"no package: {use.path} ({use.why}) belongs to no Debian package; install it "
              f"from one and list that package in {packages_file}")
    if len(unowned) > 20:
        print(f"  ... and {len(unowned) - 20} more files that belong to no package")
    if missing or unowned:
        return 1
    print(f"package check: {checked} files from outside the repository, all from packages in "
          f"the closure of {packages_file} ({len(listed)} listed, {len(allowed)} in the closure)")
    return 0


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("build_dir")
    parser.add_argument("--packages", help="the package list (default: scripts/packages.txt)")
    parser.add_argument("--deps", help="a `ninja -t deps` listing instead of the build's own")
    parser.add_argument("--link", help="link-line items, one a line, instead of build.ninja's")
    parser.add_argument("--probe-tests", metavar="REGEX",
                        help="run the ctest tests matching REGEX under strace and check what "
                             "they open and run")
    parser.add_argument("--opened", help="an strace log of the tests, instead of --probe-tests")
    parser.add_argument("--no-runtime", action="store_true",
                        help="skip ldd of the built programs and CMake's programs")
    parser.add_argument("--compiler", default="c++")
    args = parser.parse_args()

    repo = os.path.realpath(os.path.join(os.path.dirname(__file__), ".."))
    build_dir = os.path.realpath(args.build_dir)
    packages_file = args.packages or os.path.join(repo, "scripts", "packages.txt")
    for what, path in (("build folder", build_dir), ("package list", packages_file)):
        if not os.path.exists(path):
            print(f"check-packages: error: {what} {path} does not exist", file=sys.stderr)
            return 2

    uses: list[Use] = []
    if args.deps:
        with open(args.deps, encoding="utf-8", errors="replace") as deps:
            uses += headers_from_deps(deps.read(), f"read by the compiler ({args.deps})")
    else:
        uses += headers_from_deps(run(["ninja", "-C", build_dir, "-t", "deps"]),
                                  "read by the compiler")
        if not uses:
            print(f"check-packages: error: {build_dir} has no dependency records (build first)",
                  file=sys.stderr)
            return 1
    if args.link:
        with open(args.link, encoding="utf-8") as items:
            uses += resolve_link_items([i.strip() for i in items if i.strip()], args.compiler)
    elif not args.deps:
        uses += resolve_link_items(link_inputs(os.path.join(build_dir, "build.ninja")),
                                   args.compiler)
    if not args.no_runtime and not args.deps:
        executables = [f for f in glob.glob(os.path.join(build_dir, "bin", "*"))
                       if os.path.isfile(f) and os.access(f, os.X_OK)]
        uses += ldd_libraries(executables)
        uses += programs_from_cache(build_dir)
    if args.probe_tests:
        if shutil.which("strace") is None:
            print(f"check-packages: error: strace is not installed (it is in {packages_file}; "
                  "run scripts/setup.sh)", file=sys.stderr)
            return 1
        with tempfile.TemporaryDirectory(prefix="luxel-package-probe-") as folder:
            log_file = os.path.join(folder, "strace.log")
            probe_tests(build_dir, args.probe_tests, log_file)
            uses += opened_from_strace(log_file)
    elif args.opened:
        uses += opened_from_strace(args.opened)

    db = load_packages()
    return check(uses, db, read_listed(packages_file), [repo, build_dir], packages_file)


if __name__ == "__main__":
    sys.exit(main())
