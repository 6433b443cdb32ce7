"""Bird & Hulstrom's (1981) clear-sky irradiance by pvlib's own implementation.

`eval::measured::broadband` writes the model of R. E. Bird and R. L. Hulstrom (1981, SERI/
TR-642-761) from the report. This script gives the same quantities from pvlib's independent
implementation (`pvlib.clearsky.bird`, with the relative air mass of Kasten 1966 and the
report's forward-scattering share Ba = 0.84), for the cases its tests pin:

    noon:  zenith 30 deg, 1013.25 hPa, ozone 0.3 cm, water 1.5 cm, AOD 0.15 (380 nm) and
           0.10 (500 nm), albedo 0.2, 1367 W/m^2
    hazy:  zenith 60 deg, 911.9 hPa (pressure ratio 0.9), ozone 0.35 cm, water 3 cm, AOD 0.45
           and 0.30, albedo 0.3, 1367 W/m^2 x 0.97 (the Earth far from the Sun)

Needs pvlib (`pip install pvlib`; 0.16.1 gave the numbers in the tests).
Run from anywhere: python3 tests/scripts/bird_hulstrom_pvlib.py
"""

import pvlib

CASES = {
    "noon": dict(zenith=30.0, pressure_ratio=1.0, ozone=0.3, water=1.5, aod380=0.15,
                 aod500=0.10, albedo=0.2, scale=1.0),
    "hazy": dict(zenith=60.0, pressure_ratio=0.9, ozone=0.35, water=3.0, aod380=0.45,
                 aod500=0.30, albedo=0.3, scale=0.97),
}

print(f"pvlib {pvlib.__version__}: W/m^2")
for name, c in CASES.items():
    airmass = pvlib.atmosphere.get_relative_airmass(c["zenith"], model="kasten1966")
    r = pvlib.clearsky.bird(c["zenith"], airmass, c["aod380"], c["aod500"], c["water"],
                            ozone=c["ozone"], pressure=101325.0 * c["pressure_ratio"],
                            dni_extra=1367.0 * c["scale"], asymmetry=0.84,
                            albedo=c["albedo"])
    print(f"{name}: global {float(r['ghi']):.2f}, direct horizontal "
          f"{float(r['direct_horizontal']):.2f}")
