"""Studies from Python: run_study runs ``pathlab study``'s runner, Study reads
a study directory (results.csv, results.json, analysis.json; the layout is
docs/study-output.md)."""

import csv
import json
import os

from . import _pathlab


def run_study(spec, out_dir, resume=True, threads=0):
    """Run a study into out_dir and return it as a Study.

    spec: a spec file (.toml; docs/study-spec.toml), a preset name ("seed",
        "quick", "full"), or TOML text (relative scene paths against the
        working directory).
    resume: continue the study in out_dir, skipping finished cells (a fresh
        directory works too); False requires an empty directory.
    threads: worker threads, 0 = all cores. The results equal ``pathlab
        study``'s: same cells, same images, same metrics.

    The GIL is released while the study runs. Raises ValueError for a bad
    spec or directory, with the command line's message.
    """
    spec = os.fspath(spec)
    if "\n" in spec or "=" in spec:
        source = "toml"
    elif spec in _pathlab.study_presets() and not os.path.exists(spec):
        source = "preset"
    else:
        source = "file"
    if isinstance(threads, bool) or not isinstance(threads, int):
        raise ValueError("threads must be an integer, got %r" % (threads,))
    _pathlab.run_study(spec, source, os.fspath(out_dir), bool(resume), threads)
    return Study(out_dir)


def _number(text):
    if text == "":
        return None
    for convert in (int, float):
        try:
            return convert(text)
        except ValueError:
            pass
    return text


class Study:
    """A study directory, read: cells (one row per scene × sampler × spp ×
    seed, the columns of results.csv), references and analysis.

    cells and references are pandas DataFrames when pandas is installed, else
    lists of dicts; analysis is analysis.json as a dict.
    """

    def __init__(self, path):
        self.path = os.fspath(path)
        results = os.path.join(self.path, "results.csv")
        if not os.path.isfile(results):
            raise ValueError("%s is not a finished study: it has no results.csv" % self.path)
        with open(results, newline="") as f:
            rows = [{k: _number(v) for k, v in row.items()} for row in csv.DictReader(f)]
        with open(os.path.join(self.path, "results.json")) as f:
            everything = json.load(f)
        with open(os.path.join(self.path, "analysis.json")) as f:
            self.analysis = json.load(f)
        references = everything.get("references", [])
        try:
            import pandas
        except ImportError:
            self.cells, self.references = rows, references
        else:
            self.cells = pandas.read_csv(results)
            self.references = pandas.DataFrame(references)

    def image_path(self, cell):
        """The path of a cell's image (a row of cells)."""
        return os.path.join(self.path, cell["image"])

    def __repr__(self):
        return "pathlab.Study(%r, %d cells)" % (self.path, len(self.cells))
