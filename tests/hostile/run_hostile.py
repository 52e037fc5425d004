#!/usr/bin/python3
"""Runs luxel-prep, luxel-sandbox and luxel-ref on every case of the hostile corpus (issue 25)
under a wall-clock timeout and an address-space limit, with strace watching open() and
execve(), and asserts for every (case, tool):

  OK-success  exit 0, the output exists and holds only finite values
  OK-error    exit 1 with one "<tool>: error: ..." line naming the level file

and reports as defects: SIGNAL, SANITIZER (a report from ASan or UBSan in a sanitized build),
TIMEOUT, OOM (bad_alloc or "out of memory", even when caught:
the file got the tool to exhaust the limit), EXIT-OTHER, UNNAMED (exit 1 whose message does
not name the file), NONFINITE, NO-OUTPUT, ESCAPE (a file opened outside the level's folder and
the tool's own installation, or a case's forbidden target), EXEC (a process spawned), WROTE
(a file created or changed in the level's folder), REJECTED-VALID (a case that must load
exited 1), and NOT-RUN (the tool could not be started; no verdict, counted as failed).

    run_hostile.py [--corpus DIR] [--generate] [--bin DIR] [--tools prep,sandbox,ref]
                   [--case REGEX] [--class REGEX] [--timeout S] [--memory-mb MB] [--jobs N]
                   [--json OUT] [--no-strace] [--no-big] [--keep]

Exit status: 0 when every run passed, 1 when any defect was found, 2 on a usage error.
"""

import argparse
import concurrent.futures
import json
import os
import re
import resource
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
sys.dont_write_bytecode = True  # keep the source tree free of __pycache__
sys.path.insert(0, HERE)

import hostile_checks as checks  # noqa: E402

EXE = {"prep": "luxel-prep", "sandbox": "luxel-sandbox", "ref": "luxel-ref"}
DEFECTS = ("SIGNAL", "SANITIZER", "TIMEOUT", "OOM", "EXIT-OTHER", "UNNAMED", "NONFINITE",
           "NO-OUTPUT", "ESCAPE", "EXEC", "WROTE", "REJECTED-VALID", "NOT-RUN")
# Process groups of the runs in flight, killed if the runner itself is interrupted.
LIVE = set()
OOM_HINT = re.compile(r"bad_alloc|out[ _]of[ _]memory|cannot allocate memory|length_error|"
                      r"vector::_M_|larger than max_size|hard rss limit exhausted", re.I)
# A report from AddressSanitizer or UndefinedBehaviorSanitizer (sanitized tools): a defect
# whatever the exit status, since UBSan's findings exit 1 like a clean error would.
SANITIZER_REPORT = re.compile(r"^(==\d+==ERROR: (Address|Leak)Sanitizer|SUMMARY: \w+Sanitizer|"
                              r".*: runtime error: )", re.M)


def command(tool, exe, level, out, threads, extra):
    if tool == "prep":
        cmd = [exe, level, "-o", os.path.join(out, "prepared.glb")]
    elif tool == "sandbox":
        cmd = [exe, "--level", level, "--gl", "egl", "--frames", "2", "--size", "64x48",
               "--warm-up-ms", "0", "--out", os.path.join(out, "frames"), "--exr"]
    else:
        cmd = [exe, "--level", level, "-o", os.path.join(out, "ref.exr"), "--spp", "1",
               "--passes", "1", "--width", "32", "--height", "24", "--photons", "1000",
               "--indirect-photons", "1000"]
    return cmd + ["--threads", str(threads)] + list(extra)


def snapshot(folder):
    state = {}
    for dirpath, dirnames, filenames in os.walk(folder):
        for name in dirnames + filenames:
            p = os.path.join(dirpath, name)
            try:
                st = os.lstat(p)
            except OSError:
                continue
            state[p] = (st.st_size, st.st_mtime_ns)
    return state


def allowed_prefixes(args, out):
    home = os.path.expanduser("~")
    build = os.path.dirname(os.path.realpath(args.bin))
    return ["/usr/", "/lib/", "/lib64/", "/etc/ld.so", "/etc/glvnd/", "/etc/drirc",
            "/etc/localtime", "/proc/", "/sys/", "/dev/null", "/dev/urandom", "/dev/random",
            "/dev/dri/", "/tmp/.X11-unix/", os.path.realpath(args.shaders) + "/", build + "/",
            os.path.realpath(out) + "/", os.path.join(home, ".cache", "mesa_shader_cache"),
            os.path.join(args.cache_home, "mesa_shader_cache")]


def forbidden_paths(entry, corpus):
    out = []
    for p in entry["forbidden"]:
        p = os.path.expanduser(p)
        out.append(p if os.path.isabs(p) else os.path.join(corpus, p))
    return out


def watch_opens(events, case_dir, out, entry, args):
    """Escapes and extra processes seen in the strace log."""
    case_real = os.path.realpath(case_dir)
    prefixes = allowed_prefixes(args, out)
    forbidden = forbidden_paths(entry, args.corpus)
    escapes, execs, attempts = [], [], []
    first_exec = True
    # A file the level names can only be opened once the level has been read: before the
    # first open inside the case's folder, a forbidden target is the process's own doing (the
    # sanitizer runtime reads /proc/self/environ before main), not the level's.
    level_read = False
    for call, requested, real, ok in events:
        if call == "execve":
            if ok and not first_exec:
                execs.append(requested)
            first_exec = first_exec and not ok
            continue
        level_read = level_read or checks.inside(real or os.path.realpath(requested), case_real)
        hit = [f for f in forbidden if level_read and (
            checks.inside(requested, f) or (real and checks.inside(real, os.path.realpath(f))))]
        if not ok:
            if hit:
                attempts.append(requested)
            continue
        where = real or os.path.realpath(requested)
        if hit:
            escapes.append("%s -> %s (forbidden target)" % (requested, where))
        elif not checks.inside(where, case_real) and not any(
                where.startswith(p) for p in prefixes):
            escapes.append("%s -> %s" % (requested, where) if where != requested else where)
    return sorted(set(escapes)), execs, sorted(set(attempts))


def first_error_line(stderr, tool):
    for line in stderr.splitlines():
        if line.startswith(EXE[tool] + ": error:"):
            return line
    return None


def check_outputs(tool, out):
    """(defect or None, note) for a run that exited 0."""
    if tool == "prep":
        glb = os.path.join(out, "prepared.glb")
        if not os.path.exists(glb):
            return "NO-OUTPUT", "no prepared.glb"
        scan = checks.scan_glb(glb)
        if scan.get("problems"):
            return "NONFINITE", "; ".join(scan["problems"][:3])
        return None, ""
    if tool == "sandbox":
        frames = os.path.join(out, "frames")
        exrs = sorted(f for f in os.listdir(frames) if f.endswith(".exr")) if os.path.isdir(
            frames) else []
        if not exrs or not os.path.exists(os.path.join(frames, "frame_0001.png")):
            return "NO-OUTPUT", "frames missing"
        bad = []
        for name in exrs:
            scan = checks.scan_exr(os.path.join(frames, name))
            if scan.get("nonfinite"):
                bad.append("%s: %d non-finite values in %d pixels" % (
                    name, scan["nonfinite"], scan["pixels"]))
        report = os.path.join(frames, "report.json")
        if os.path.exists(report):
            bad += ["report.json " + p for p in checks.scan_json_file(report)[:3]]
        black = all(checks.scan_exr(os.path.join(frames, n)).get("black") for n in exrs)
        return ("NONFINITE", "; ".join(bad)) if bad else (None, "black frame" if black else "")
    exr = os.path.join(out, "ref.exr")
    if not os.path.exists(exr):
        return "NO-OUTPUT", "no ref.exr"
    scan = checks.scan_exr(exr)
    if not scan["checked"]:
        return None, "EXR not checked: " + scan["why"]
    if scan["nonfinite"]:
        return "NONFINITE", "ref.exr: %d non-finite values in %d pixels" % (
            scan["nonfinite"], scan["pixels"])
    return None, "black frame" if scan["black"] else ""


def run_one(entry, tool, args):
    level = os.path.join(args.corpus, entry["file"])
    case_dir = os.path.dirname(level)
    out = tempfile.mkdtemp(prefix="hostile-%s-%s-" % (tool, entry["name"][:40]),
                           dir=args.work_dir)
    try:
        return _run_in(entry, tool, args, level, case_dir, out)
    finally:
        if not args.keep:
            shutil.rmtree(out, ignore_errors=True)


def _limits(memory_bytes):
    """RLIMIT_AS for a plain build; none for a sanitized one (memory_bytes 0), whose shadow
    memory alone reserves terabytes of address space: sanitizer_environment() bounds it."""
    def apply():
        if memory_bytes:
            resource.setrlimit(resource.RLIMIT_AS, (memory_bytes, memory_bytes))
        resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
    return apply


def sanitizer_environment(environ, memory_mb, strace):
    """The memory limit of a sanitized run, set through AddressSanitizer: one allocation larger
    than the limit returns null (so operator new throws bad_alloc, as it would under RLIMIT_AS),
    and a resident set larger than the limit ends the run with a report read as OOM.
    LeakSanitizer cannot run under ptrace (strace), so leaks are left to the test suite then.
    Allocations are traced with the fast unwinder: fast_unwind_on_malloc=0 deadlocks when
    llvmpipe compiles a shader (LLVM registers the JIT's unwind tables, libgcc takes its object
    lock to sort them and allocates under it, and ASan's slow unwinder inside that malloc waits
    for the same lock). Every sanitized sandbox run of the corpus that drew a frame hung; the
    test suite, which used it too, now also uses the fast unwinder (tests/CMakeLists.txt). Set
    here all the same, since a caller's environment may ask for the slow one.
    The options are appended to the caller's: later options win."""
    asan = ["allocator_may_return_null=1", "max_allocation_size_mb=%d" % memory_mb,
            "hard_rss_limit_mb=%d" % memory_mb, "fast_unwind_on_malloc=1"]
    if strace:
        asan.append("detect_leaks=0")
    env = dict(environ)
    env["ASAN_OPTIONS"] = ":".join(o for o in [environ.get("ASAN_OPTIONS", "")] + asan if o)
    env["UBSAN_OPTIONS"] = ":".join(
        o for o in [environ.get("UBSAN_OPTIONS", ""), "print_stacktrace=1", "halt_on_error=1"]
        if o)
    return env


def is_sanitized(exe):
    """Whether the tool links AddressSanitizer's runtime (GCC links libasan dynamically)."""
    try:
        out = subprocess.run(["ldd", exe], capture_output=True, text=True, timeout=30).stdout
    except (OSError, subprocess.TimeoutExpired):
        return False
    return "libasan" in out


def _run_in(entry, tool, args, level, case_dir, out):
    cmd = command(tool, os.path.join(args.bin, EXE[tool]), level, out, args.threads,
                  entry["args"].get(tool, []))
    log = os.path.join(out, "strace.log")
    if args.strace:
        cmd = [args.strace, "-f", "-qq", "-y", "-s", "4096", "-o", log,
               "-e", "trace=open,openat,openat2,creat,execve"] + cmd
    # Levels the tools prepare at load are cached in the run's own folder, the one place
    # besides Mesa's shader cache they may write.
    env = dict(os.environ, EGL_PLATFORM="surfaceless", XDG_CACHE_HOME=args.cache_home,
               LUXEL_CACHE_DIR=os.path.join(out, "prep-cache"))
    if args.sanitized:
        env = sanitizer_environment(env, args.memory_mb, args.strace)
    before = snapshot(case_dir)
    started = time.monotonic()
    with open(os.path.join(out, "stdout"), "wb") as so, open(os.path.join(out, "stderr"),
                                                             "wb") as se:
        try:
            proc = subprocess.Popen(cmd, cwd=out, env=env, stdout=so, stderr=se,
                                    stdin=subprocess.DEVNULL, start_new_session=True,
                                    preexec_fn=_limits(
                                        0 if args.sanitized else args.memory_mb << 20))
        except OSError as e:  # the tool is missing or not executable (being relinked)
            return {"case": entry["name"], "class": entry["class"], "tool": tool, "rc": None,
                    "seconds": 0.0, "peak_mb": 0, "defects": ["NOT-RUN"], "note": str(e),
                    "message": "", "verdict": "NOT-RUN"}
        LIVE.add(proc.pid)
        timed_out = threading.Event()

        def kill():
            timed_out.set()
            try:
                os.killpg(proc.pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
        timer = threading.Timer(args.timeout, kill)
        timer.start()
        _, status, usage = os.wait4(proc.pid, 0)
        timer.cancel()
        LIVE.discard(proc.pid)
        proc.returncode = os.waitstatus_to_exitcode(status)
        # Whatever the tool left behind in its group (a helper thread's process) goes too.
        try:
            os.killpg(proc.pid, signal.SIGKILL)
        except (ProcessLookupError, PermissionError):
            pass
    seconds = time.monotonic() - started
    with open(os.path.join(out, "stderr"), "rb") as f:
        stderr = f.read().decode(errors="replace")
    rc = proc.returncode
    result = {"case": entry["name"], "class": entry["class"], "tool": tool, "rc": rc,
              "seconds": round(seconds, 2), "peak_mb": usage.ru_maxrss // 1024,
              "defects": [], "note": ""}
    error_line = first_error_line(stderr, tool)
    result["message"] = (error_line or (stderr.strip().splitlines() or [""])[-1])[:400]
    defects = result["defects"]

    if re.search(r"^\S*strace: (exec|Can't stat)", stderr, re.M):
        # The tool could not be started (being relinked, missing): no verdict on the case.
        defects.append("NOT-RUN")
        result["note"] = "the tool did not start"
    elif SANITIZER_REPORT.search(stderr) and not re.search("hard rss limit exhausted", stderr):
        defects.append("SANITIZER")
        result["note"] = SANITIZER_REPORT.search(stderr).group(0).strip()[:200]
    elif timed_out.is_set():
        defects.append("TIMEOUT")
        result["note"] = "killed after %d s" % args.timeout
    elif rc < 0:
        name = signal.Signals(-rc).name if -rc in signal.valid_signals() else str(-rc)
        defects.append("OOM" if OOM_HINT.search(stderr) else "SIGNAL")
        result["note"] = name
    elif rc == 0:
        try:
            defect, note = check_outputs(tool, out)
        except Exception as e:  # a malformed output is itself a finding
            defect, note = "NONFINITE", "output unreadable: %s" % e
        if defect:
            defects.append(defect)
        result["note"] = note
    elif rc == 1:
        if OOM_HINT.search(stderr):
            defects.append("OOM")
        elif error_line is None or not (os.path.basename(level) in error_line or
                                        case_dir in error_line):
            defects.append("UNNAMED")
        if entry["expect"] == "success":
            defects.append("REJECTED-VALID")
    else:
        defects.append("EXIT-OTHER")
        result["note"] = "exit %d" % rc

    if args.strace:
        events = checks.parse_strace(log, out)
        escapes, execs, attempts = watch_opens(events, case_dir, out, entry, args)
        if escapes:
            defects.append("ESCAPE")
            result["escapes"] = escapes[:10]
        if execs:
            defects.append("EXEC")
            result["execs"] = execs[:10]
        if attempts:
            result["attempted"] = attempts[:10]
    if os.path.exists(os.path.join(out, "pwned")):
        defects.append("EXEC")
    after = snapshot(case_dir)
    changed = sorted(p for p in after if before.get(p) != after[p])
    if changed:
        defects.append("WROTE")
        result["wrote"] = changed[:10]
    result["verdict"] = ",".join(defects) if defects else (
        "OK-success" if rc == 0 else "OK-error")
    return result


def load_manifest(args):
    path = os.path.join(args.corpus, "manifest.json")
    if args.generate or not os.path.exists(path):
        cmd = [sys.executable, os.path.join(HERE, "gen_hostile.py"), "--out", args.corpus]
        if args.no_big:
            cmd.append("--no-big")
        if args.case:  # only what this run needs: the ctest subset writes 45 cases, not 370
            cmd += ["--case", args.case]
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL if args.quiet else None)
    with open(path) as f:
        return json.load(f)


def print_tables(results, manifest, tools, stream):
    by_case = {}
    for r in results:
        by_case.setdefault(r["case"], {})[r["tool"]] = r
    for cls, title in manifest["classes"].items():
        rows = [c for c in manifest["cases"] if c["class"] == cls and c["name"] in by_case]
        if not rows:
            continue
        print("\n## %s" % title, file=stream)
        print("%-40s " % "case" + " ".join("%-22s" % t for t in tools), file=stream)
        for c in rows:
            cells = []
            for t in tools:
                r = by_case[c["name"]].get(t)
                cells.append("%-22s" % (("%s %.1fs" % (r["verdict"], r["seconds"]))
                                        if r else "-"))
            print("%-40s " % c["name"][:40] + " ".join(cells), file=stream)
    failed = [r for r in results if r["defects"]]
    if failed:
        print("\n## defects", file=stream)
        for r in failed:
            extra = r.get("escapes") or r.get("execs") or r.get("wrote") or []
            print("%s [%s] %s: rc %s, %.1f s, %d MB, %s %s%s" % (
                r["case"], r["tool"], r["verdict"], r["rc"], r["seconds"], r["peak_mb"],
                r["note"], r["message"][:200], (" | " + "; ".join(extra[:3])) if extra else ""),
                file=stream)


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--corpus", default=os.path.join(tempfile.gettempdir(), "luxel-hostile"),
                   help="corpus folder (generated there when it has no manifest)")
    p.add_argument("--generate", action="store_true", help="regenerate the corpus first")
    p.add_argument("--bin", default=os.path.join(REPO, "build", "bin"),
                   help="folder holding luxel-prep, luxel-sandbox and luxel-ref")
    p.add_argument("--shaders", default=os.path.join(REPO, "shaders"),
                   help="the shader folder the tools may read")
    p.add_argument("--tools", default="prep,sandbox,ref")
    p.add_argument("--case", help="only cases whose name matches this regex")
    p.add_argument("--class", dest="cls", help="only classes matching this regex")
    p.add_argument("--timeout", type=float, default=30.0, help="seconds per run")
    p.add_argument("--memory-mb", type=int, default=4096,
                   help="memory limit per run: address space, or for sanitized tools the "
                        "largest allocation and the resident set")
    p.add_argument("--sanitized", choices=("auto", "yes", "no"), default="auto",
                   help="whether the tools are built with ASan and UBSan (auto: ask ldd)")
    p.add_argument("--threads", type=int, default=1, help="--threads given to every tool")
    p.add_argument("--jobs", type=int, default=1, help="runs at once")
    p.add_argument("--json", help="write every result here")
    p.add_argument("--no-strace", action="store_true", help="do not watch open()")
    p.add_argument("--no-big", action="store_true", help="skip cases marked big")
    p.add_argument("--keep", action="store_true", help="keep each run's output folder")
    p.add_argument("--work-dir", help="where the per-run output folders go")
    p.add_argument("--quiet", action="store_true", help="no progress lines")
    args = p.parse_args(argv)
    args.corpus = os.path.abspath(args.corpus)
    args.bin = os.path.abspath(args.bin)
    args.tools = [t for t in args.tools.split(",") if t]
    unknown = [t for t in args.tools if t not in EXE]
    if unknown:
        p.error("unknown tools: " + ", ".join(unknown))
    for t in args.tools:
        if not os.access(os.path.join(args.bin, EXE[t]), os.X_OK):
            p.error("%s not found in %s" % (EXE[t], args.bin))
    if args.work_dir:
        args.work_dir = os.path.abspath(args.work_dir)
        os.makedirs(args.work_dir, exist_ok=True)
    if args.sanitized == "auto":
        args.sanitized = any(is_sanitized(os.path.join(args.bin, EXE[t])) for t in args.tools)
    else:
        args.sanitized = args.sanitized == "yes"
    args.strace = None if args.no_strace else shutil.which("strace")
    if not args.no_strace and not args.strace:
        print("run_hostile.py: strace not found; escapes are not watched", file=sys.stderr)
    # Mesa finds its shader cache through getpwuid() (reading /etc/passwd) unless told where;
    # pointing it there keeps the tools' own opens out of the escape report.
    args.cache_home = os.environ.get("XDG_CACHE_HOME") or os.path.expanduser("~/.cache")
    return args


def _interrupted(signum, frame):
    for group in list(LIVE):
        try:
            os.killpg(group, signal.SIGKILL)
        except (ProcessLookupError, PermissionError):
            pass
    print("run_hostile.py: interrupted (signal %d)" % signum, file=sys.stderr)
    os._exit(128 + signum)


def main(argv):
    args = parse_args(argv)
    for signum in (signal.SIGINT, signal.SIGTERM):
        signal.signal(signum, _interrupted)
    manifest = load_manifest(args)
    runs = [(c, t) for c in manifest["cases"] for t in args.tools
            if t in c["tools"] and (not args.case or re.search(args.case, c["name"]))
            and (not args.cls or re.search(args.cls, c["class"]))
            and not (args.no_big and c.get("big"))]
    # The tools may be rebuilt under a long run; the report says so rather than mixing builds
    # silently.
    stamp = {t: os.stat(os.path.join(args.bin, EXE[t])).st_mtime for t in args.tools}
    results = []
    lock = threading.Lock()

    def one(item):
        r = run_one(item[0], item[1], args)
        with lock:
            results.append(r)
            if not args.quiet:
                print("[%d/%d] %-40s %-8s %-16s %5.1fs %s" % (
                    len(results), len(runs), r["case"][:40], r["tool"], r["verdict"],
                    r["seconds"], r["message"][:100]), file=sys.stderr, flush=True)
        return r

    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
        list(pool.map(one, runs))
    order = {(c["name"], t): i for i, (c, t) in enumerate(runs)}
    results.sort(key=lambda r: order[(r["case"], r["tool"])])
    print_tables(results, manifest, args.tools, sys.stdout)
    rebuilt = [EXE[t] for t in args.tools
               if os.stat(os.path.join(args.bin, EXE[t])).st_mtime != stamp[t]]
    if rebuilt:
        print("\nwarning: %s changed during the run; results mix builds" % ", ".join(rebuilt))
    failed = sum(1 for r in results if r["defects"])
    print("\n%d passed, %d failed" % (len(results) - failed, failed))
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"timeout": args.timeout, "memory_mb": args.memory_mb,
                       "sanitized": args.sanitized,
                       "binaries": {EXE[t]: time.strftime("%Y-%m-%dT%H:%M:%S",
                                                          time.gmtime(stamp[t]))
                                    for t in args.tools},
                       "rebuilt_during_run": rebuilt, "results": results}, f, indent=1)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
