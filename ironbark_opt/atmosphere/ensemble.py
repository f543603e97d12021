"""NCEP GEFS ensemble members over a site, through THREDDS NCSS.

UCAR's THREDDS serves the GEFS members as one GRIB collection,
``grib/NCEP/GEFS/Global_1p0deg_Ensemble/members`` (its "Best" time series:
``.../members/Best``; the path named in Unidata's Siphon examples and the
THREDDS test catalogues).  netCDF-Java names a GRIB variable with an ensemble
dimension with the suffix ``_ens`` (``Temperature_isobaric_ens``,
``u-component_of_wind_isobaric_ens``, ...) and gives it an axis of
``axisType="Ensemble"`` named ``ens`` whose values are the GRIB2 perturbation
numbers, 0 being the control run (``GribCoverageDataset.makeCoordAxis(CoordinateEns)``).
A member is asked for with ``ensCoord=<number>`` (TDS 5,
``NcssGridParamsBean.ensCoord``), one request per member and vertical axis,
each cached by :mod:`ironbark_opt.net` like the RAP/GFS requests.
Numeric-only (I/O).
"""
from __future__ import annotations

from ironbark_opt.atmosphere import ncss
from ironbark_opt.errors import InputError

#: NCSS dataset path of the GEFS members below the THREDDS base URL
GEFS_PATH = "ncss/grid/grib/NCEP/GEFS/Global_1p0deg_Ensemble/members/Best"
#: the isobaric variables of an ensemble dataset (netCDF-Java's ``_ens`` suffix)
ENSEMBLE_VARIABLES = {key: name + "_ens" for key, name in ncss.VARIABLES.items()}


def ensemble_members(dataset_url: str, source: str = "THREDDS GEFS") -> tuple[int, ...]:
    """Member numbers of the dataset's Ensemble axis (control first), read from ``dataset.xml``.

    Raises InputError naming the dataset and the field when a variable or its
    Ensemble axis is missing, or the four variables have different members.
    """
    info = ncss.dataset_info(dataset_url, source)
    where = f"{dataset_url}/dataset.xml"
    missing = [v for v in ENSEMBLE_VARIABLES.values() if v not in info.vertical_axis]
    if missing:
        raise InputError(f"the dataset has no {', '.join(missing)}", source=where, field=missing[0])
    no_axis = [v for v in ENSEMBLE_VARIABLES.values() if v not in info.ensemble]
    if no_axis:
        raise InputError(f"{no_axis[0]} has no ensemble axis (axisType=\"Ensemble\"): not an ensemble "
                         "dataset", source=where, field=no_axis[0])
    sets = {info.ensemble[v][1] for v in ENSEMBLE_VARIABLES.values()}
    if len(sets) != 1:
        raise InputError("the four isobaric variables have different ensemble members", source=where,
                         field=info.ensemble[ENSEMBLE_VARIABLES["height"]][0])
    values = sets.pop()
    if any(abs(v - round(v)) > 1e-9 or v < 0 for v in values):
        raise InputError(f"ensemble axis values {list(values)} are not perturbation numbers", source=where,
                         field=info.ensemble[ENSEMBLE_VARIABLES["height"]][0])
    return tuple(sorted(int(round(v)) for v in values))


def choose_members(available, count: int | None, dataset: str) -> tuple[int, ...]:
    """The first ``count`` members (control first; all when None)."""
    if count is None:
        return tuple(available)
    if isinstance(count, bool) or not isinstance(count, int) or not 1 <= count <= len(available):
        raise InputError(f"{count!r} members asked; the dataset {dataset} has {len(available)} "
                         f"(members {available[0]}..{available[-1]})", field="--members")
    return tuple(available[:count])


def member_columns(dataset_url: str, latitude: float, longitude: float, time, member: int,
                   source: str = "THREDDS GEFS") -> dict:
    """:func:`ncss.point_columns` of one member (which checks it is on the variables' Ensemble axis)."""
    return ncss.point_columns(dataset_url, latitude, longitude, time, source=f"{source} member {member}",
                              variables=ENSEMBLE_VARIABLES, member=member)
