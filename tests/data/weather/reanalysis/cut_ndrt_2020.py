"""Cut ndrt_2020_weather_data_ERA5_new.nc (2.4 MB, 97 x 101 grid) to the 5 x 5
points around the Notre Dame launch site (41.775 N, 86.572 W) that the
bilinear interpolation uses, keeping every variable, attribute and level:

    python cut_ndrt_2020.py SRC DST

SRC: ../shared/fixtures/weather/reanalysis/ndrt_2020_weather_data_ERA5_new.nc.
The test tests/validation/test_real_flights.py checks that the cut file gives
the same profile as the full one when the latter is present.
"""
import sys

import h5py
import numpy as np

LAT = (41.0, 42.5)      # [deg] window kept (inclusive)
LON = (-87.5, -86.0)


def cut(src, dst):
    with h5py.File(src, "r") as a, h5py.File(dst, "w") as b:
        lat, lon = a["latitude"][()], a["longitude"][()]
        iy = np.flatnonzero((lat >= LAT[0]) & (lat <= LAT[1]))
        ix = np.flatnonzero((lon >= LON[0]) & (lon <= LON[1]))
        sub = {"latitude": iy, "longitude": ix}
        skip = ("DIMENSION_LIST", "REFERENCE_LIST", "CLASS", "NAME", "_Netcdf4Dimid",
                "_Netcdf4Coordinates")
        axes = ("valid_time", "pressure_level", "latitude", "longitude")
        for name in axes:
            data = a[name][()]
            if name in sub:
                data = data[sub[name]]
            ds = b.create_dataset(name, data=data)
            ds.make_scale(name)
            for k, v in a[name].attrs.items():
                if k not in skip:
                    ds.attrs[k] = v
        for name in ("z", "t", "u", "v"):
            data = a[name][()][:, :, iy][:, :, :, ix]
            ds = b.create_dataset(name, data=data)
            for k, v in a[name].attrs.items():
                if k not in skip:
                    ds.attrs[k] = v
            for i, axis in enumerate(axes):
                ds.dims[i].attach_scale(b[axis])


if __name__ == "__main__":
    cut(sys.argv[1], sys.argv[2])
