#!/usr/bin/python3
"""scripts/validation.py's study_hours: the span of a study from its runs' start and end
times, when a run was resumed from its checkpoint.

    /usr/bin/python3 tests/scripts/test_validation_hours.py

A resumed run's `started` is the start of its last part; its `wall_seconds` counts the
parts before. Needs no build: the runs are stand-ins with the three attributes.
"""
import os
import sys
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "scripts"))

from validation import study_hours  # noqa: E402


class Run:
    def __init__(self, started, finished, wall_seconds):
        self.attributes = {"started": started, "finished": finished,
                           "wall_seconds": wall_seconds}

    def attribute(self, name):
        return self.attributes[name]


class StudyHours(unittest.TestCase):
    def test_runs_that_ran_through_span_first_start_to_last_end(self):
        runs = [Run("2026-12-05T19:48:00Z", "2026-12-05T21:00:00Z", 4310.0),
                Run("2026-12-05T21:00:00Z", "2026-12-05T22:30:00Z", 5390.0)]
        self.assertAlmostEqual(study_hours(runs), 2.7)

    def test_a_resumed_run_counts_from_its_end_less_its_own_time(self):
        # Ran 78 minutes from 19:48, killed; resumed at 21:27 and finished at 21:36:
        # 87 minutes of its own. The other ran through from 21:36 to 22:36.
        runs = [Run("2026-12-05T21:27:00Z", "2026-12-05T21:36:00Z", 87 * 60.0),
                Run("2026-12-05T21:36:00Z", "2026-12-05T22:36:00Z", 60 * 60.0)]
        # From 20:09 (21:36 less 87 minutes) to 22:36, not from the resume at 21:27.
        self.assertAlmostEqual(study_hours(runs), 2.45)

    def test_unreadable_times_give_none(self):
        self.assertIsNone(study_hours([Run("yesterday", "2026-12-05T22:36:00Z", 60.0)]))


if __name__ == "__main__":
    unittest.main(verbosity=2)
