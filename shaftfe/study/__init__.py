"""Design studies (``shaftfe study``): many designs of a base variant on Dask.distributed.

``spec`` (the study file) → ``sampling`` (the designs) → ``evaluate`` (one design → one row,
through the package's analyses) → ``runner`` (Dask, cache, resume, sharing) → ``results``
(Parquet/CSV, non-dominated, sensitivities) → ``report`` (HTML). docs/STUDIES.md.
"""
