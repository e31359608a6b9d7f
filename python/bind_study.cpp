// pathlab.run_study: `pathlab study`'s runner (study/runner.h) on a spec file,
// a preset or TOML text; the results are the files the CLI writes.
#include <pybind11/stl.h>

#include "bindings.h"
#include "core/error.h"
#include "study/presets.h"
#include "study/runner.h"
#include "study/spec.h"

namespace pathlab::python {
namespace {

// `source` is "file" (spec is a path), "preset" (a name) or "toml" (text,
// relative scene paths against the working directory).
StudySpec studySpec(const std::string& spec, const std::string& source) {
    if (source == "file") return loadStudySpec(spec);
    if (source == "preset") return presetSpec(spec);
    if (source == "toml") return parseStudySpec(spec, "spec", ".");
    throw InputError("source must be 'file', 'preset' or 'toml', got '" + source + "'");
}

py::dict runStudyFromPython(const std::string& spec, const std::string& source,
                            const std::string& outDir, bool resume, int threads) {
    const StudyOptions options{outDir, resume, threads};
    StudyRun run;
    {
        py::gil_scoped_release release;
        checkStudyOptions(options);  // before the spec, as the CLI does
        run = runStudy(studySpec(spec, source), options);
    }
    py::dict d;
    d["cells_rendered"] = run.cellsRendered;
    d["cells_skipped"] = run.cellsSkipped;
    d["references_rendered"] = run.referencesRendered;
    d["references_reused"] = run.referencesReused;
    d["seconds"] = run.seconds;
    d["analysis_json"] = run.analysis.dump();
    return d;
}

}  // namespace

void bindStudy(py::module_& m) {
    m.def("run_study", &runStudyFromPython, py::arg("spec"), py::arg("source"), py::arg("out_dir"),
          py::arg("resume"), py::arg("threads"));
    m.def("study_presets", &presetNames);
}

}  // namespace pathlab::python
