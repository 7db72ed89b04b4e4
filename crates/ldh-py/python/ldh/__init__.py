"""ldh: gait assessment for lumbar disc herniation from two shank-worn IMUs.

All computation happens in the Rust core (``ldh._ldh``) with the GIL released; this package
converts inputs to float64 numpy arrays, results to pandas DataFrames (when pandas is
importable) and scipy/nolds-shaped objects, and documents the API (docs/python.md).
"""
from . import _ldh
from ._errors import (
    LdhDataError,
    LdhError,
    LdhFileNotFoundError,
    LdhOSError,
    LdhParamError,
    LdhTypeError,
    LdhWarning,
)
from ._agreement import Agreement, agree, reliability
from ._io import butter_filtfilt, preprocess, read_recording, simulate_cohort, write_demo
from ._ml import cross_validate, predict, train
from ._monitor import MonitorResult, monitor
from ._nonlinear import lyap_e, lyap_r
from ._pipeline import analyze, analyze_many, analyze_pair, analyze_recording
from ._result import Result
from ._stats import (
    ConfidenceInterval,
    TestResult,
    f_oneway,
    holm,
    kruskal,
    mannwhitneyu,
    pearsonr,
    shapiro,
    ttest_ind,
    ttest_1samp,
    ttest_rel,
    wilcoxon,
)

__version__ = _ldh.__version__
__all__ = [
    "agree",
    "Agreement",
    "reliability",
    "LdhError",
    "LdhDataError",
    "LdhParamError",
    "LdhTypeError",
    "LdhFileNotFoundError",
    "LdhOSError",
    "LdhWarning",
    "read_recording",
    "butter_filtfilt",
    "preprocess",
    "write_demo",
    "simulate_cohort",
    "analyze",
    "analyze_many",
    "analyze_recording",
    "analyze_pair",
    "monitor",
    "MonitorResult",
    "Result",
    "lyap_r",
    "lyap_e",
    "shapiro",
    "mannwhitneyu",
    "ttest_ind",
    "ttest_rel",
    "wilcoxon",
    "f_oneway",
    "kruskal",
    "pearsonr",
    "holm",
    "TestResult",
    "ConfidenceInterval",
    "ttest_1samp",
    "cross_validate",
    "train",
    "predict",
]
