#!/usr/bin/python3
"""Checks of the hostile-corpus runner's own verdicts (run_hostile.py): an escape through the
level is found, and what is not the level's doing is not called one. Standard library only;
ctest `hostile_runner_checks`."""

import os
import sys
import types
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import run_hostile  # noqa: E402


class WatchOpens(unittest.TestCase):
    def setUp(self):
        self.corpus = "/tmp/corpus"
        self.case = os.path.join(self.corpus, "esc-case")
        self.level = os.path.join(self.case, "esc-case.gltf")
        self.out = "/tmp/runs/esc-case-prep"
        self.args = types.SimpleNamespace(bin="/opt/luxel/build/bin",
                                          shaders="/opt/luxel/shaders",
                                          cache_home="/root/.cache", corpus=self.corpus)
        self.entry = {"forbidden": ["/proc/self/environ"]}

    def watch(self, events):
        return run_hostile.watch_opens(events, self.case, self.out, self.entry, self.args)

    def test_a_forbidden_target_opened_after_the_level_is_an_escape(self):
        escapes, _, _ = self.watch([("openat", self.level, self.level, True),
                                    ("openat", "/proc/self/environ", "/proc/1/environ", True)])
        self.assertEqual(len(escapes), 1)
        self.assertIn("forbidden target", escapes[0])

    def test_a_failed_attempt_after_the_level_is_an_attempt(self):
        escapes, _, attempts = self.watch([("openat", self.level, self.level, True),
                                           ("openat", "/proc/self/environ", None, False)])
        self.assertEqual(escapes, [])
        self.assertEqual(attempts, ["/proc/self/environ"])

    def test_the_sanitizer_runtime_reading_its_environment_before_main_is_not(self):
        # AddressSanitizer opens /proc/self/environ while the process starts, before any file
        # of the level could have been named.
        escapes, _, attempts = self.watch([
            ("openat", "/proc/self/environ", "/proc/1/environ", True),
            ("openat", self.level, self.level, True)])
        self.assertEqual(escapes, [])
        self.assertEqual(attempts, [])

    def test_a_file_outside_every_allowed_folder_is_an_escape_whenever_opened(self):
        escapes, _, _ = self.watch([("openat", "/home/user/secret.bin", "/home/user/secret.bin",
                                     True)])
        self.assertEqual(escapes, ["/home/user/secret.bin"])

    def test_a_second_program_started_is_reported(self):
        _, execs, _ = self.watch([("execve", "/opt/luxel/build/bin/luxel-prep", None, True),
                                  ("execve", "/bin/sh", None, True)])
        self.assertEqual(execs, ["/bin/sh"])


class SanitizerEnvironment(unittest.TestCase):
    def test_memory_is_bounded_and_allocations_use_the_fast_unwinder(self):
        env = run_hostile.sanitizer_environment(
            {"ASAN_OPTIONS": "detect_leaks=1:fast_unwind_on_malloc=0"}, 4096,
            strace="/usr/bin/strace")
        options = env["ASAN_OPTIONS"].split(":")
        # Later options win: the runner's come after the caller's.
        self.assertLess(options.index("fast_unwind_on_malloc=0"),
                        options.index("fast_unwind_on_malloc=1"))
        self.assertIn("max_allocation_size_mb=4096", options)
        self.assertIn("hard_rss_limit_mb=4096", options)
        # LeakSanitizer cannot run under ptrace.
        self.assertLess(options.index("detect_leaks=1"), options.index("detect_leaks=0"))


if __name__ == "__main__":
    unittest.main()
