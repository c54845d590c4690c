#!/usr/bin/env python3
"""Converts an NREL TMY3 CSV into an EnergyPlus weather file (EPW).

    python3 scripts/tmy3-to-epw.py TMY3.CSV OUT.epw

Standard library only (Python 3.11). The TMY3 layout is NREL's (S. Wilcox and W. Marion,
"Users Manual for TMY3 Data Sets", NREL/TP-581-43156, 2008): line 1 the site
(USAF,Name,State,TZ,latitude,longitude,elevation), line 2 the column names, then one hour a
line, each value followed by its source flag and uncertainty. The EPW layout is EnergyPlus's
data dictionary (EnergyPlus Auxiliary Programs, "Weather Converter Program"): 8 header lines,
then 35 fields a record.

What the conversion does, field by field:

- year, month, day, hour as written (hour 1-24 ends the hour, local standard time, in both
  formats); minute 60 (the end of the hour, the dictionary's range 1-60).
- Units: pressure mbar -> Pa (x100), visibility m -> km (/1000), precipitable water
  cm -> mm (x10). The illuminances are multiplied by 100 and the zenith luminance by 10: the
  TMY3 files hold them in hundreds of lux and tens of cd/m^2 (the unit of their
  documentation, though the columns are headed (lx) and (cd/m^2)); the ratio of global
  illuminance to global irradiance as written is about 1.07 "lm/W" where daylight's is
  about 107 lm/W. The EPW's unit is lux and cd/m^2.
- A value whose source flag is '?' ("source does not fit any of the above; used mostly for
  missing data" in NREL's flag tables) is written as the EPW's missing code; in the TMY3
  files these are chiefly aerosol optical depth and albedo written as 0.
- Fields TMY3 does not have are written as the EPW's missing codes: horizontal infrared
  radiation 9999, present weather observation 9 and codes 999999999, snow depth 999, days
  since last snowfall 99.
- Data source and uncertainty flags (field 6): the TMY3's own flags for the meteorological
  elements (their letters A-F and '?' and codes 0-9 are EPW's); '?9' (source unknown,
  uncertainty unknown) for the solar and illuminance elements, whose TMY3 source codes are
  numbers with no EPW letter, and for elements TMY3 does not have.
- LOCATION: city and state from line 1, country USA (the TMY3 data set's stations are of the
  USA and its territories), source TMY3, WMO the USAF number, then latitude, longitude, time
  zone and elevation as written. Commas in names become spaces (EPW fields are not quoted).
- DATA PERIODS: one period, one record per hour, "Data", starting on a Sunday (TMY months
  come from different years; EnergyPlus takes the weekday from its run period), from the
  first record's date to the last's.
"""

import csv
import sys

# The EPW's missing codes (data dictionary, the \missing of each field).
MISSING = {
    "dry_bulb": "99.9",
    "dew_point": "99.9",
    "relative_humidity": "999",
    "pressure": "999999",
    "radiation": "9999",
    "illuminance": "999999",
    "zenith_luminance": "9999",
    "wind_direction": "999",
    "wind_speed": "999",
    "sky_cover": "99",
    "visibility": "9999",
    "ceiling_height": "99999",
    "precipitable_water": "999",
    "aerosol_optical_depth": ".999",
    "snow_depth": "999",
    "days_since_snow": "99",
    "albedo": "999",
    "precipitation_depth": "999",
    "precipitation_quantity": "99",
}


def number(value):
    """A number as short as it is exact: 16.1, 101300, 0.089."""
    value = round(value, 6)
    if value == int(value):
        return str(int(value))
    return repr(value)


def convert(rows, source_name):
    """The EPW's lines for the TMY3 rows (site, column names, records)."""
    site, names, records = rows[0], rows[1], rows[2:]
    column = {name: i for i, name in enumerate(names)}

    usaf, name, state, tz, latitude, longitude, elevation = site[:7]
    clean = lambda text: text.replace(",", " ").strip()
    header = [
        f"LOCATION,{clean(name)},{clean(state)},USA,TMY3,{usaf},{latitude},{longitude},{tz},{elevation}",
        "DESIGN CONDITIONS,0",
        "TYPICAL/EXTREME PERIODS,0",
        "GROUND TEMPERATURES,0",
        "HOLIDAYS/DAYLIGHT SAVINGS,No,0,0,0",
        f"COMMENTS 1,NREL TMY3 {source_name} converted by eigenrad's scripts/tmy3-to-epw.py",
        "COMMENTS 2,illuminances x100 and zenith luminance x10 (TMY3 hundreds of lux and tens "
        "of cd/m2); values flagged ? written as missing",
    ]
    first_month, first_day, _ = records[0][column["Date (MM/DD/YYYY)"]].split("/")
    last_month, last_day, _ = records[-1][column["Date (MM/DD/YYYY)"]].split("/")
    header.append(
        f"DATA PERIODS,1,1,Data,Sunday,{int(first_month):2d}/{int(first_day):2d},"
        f"{int(last_month):2d}/{int(last_day):2d}"
    )

    lines = header
    for row in records:
        def value(name, scale=1.0, missing=None):
            i = column[name]
            if missing is not None and row[i + 1] == "?":
                return missing
            return number(float(row[i]) * scale)

        def flags(name):
            i = column[name]
            return row[i + 1] + row[i + 2]

        month, day, year = row[column["Date (MM/DD/YYYY)"]].split("/")
        hour, minutes = row[column["Time (HH:MM)"]].split(":")
        assert minutes == "00", f"not an hourly file: {row[column['Time (HH:MM)']]}"
        meteorological = [
            flags("Dry-bulb (C)"),
            flags("Dew-point (C)"),
            flags("RHum (%)"),
            flags("Pressure (mbar)"),
        ]
        solar = ["?9"] * 8  # horizontal IR, GHI, DNI, DHI, 3 illuminances, zenith luminance
        weather = [
            flags("Wdir (degrees)"),
            flags("Wspd (m/s)"),
            flags("TotCld (tenths)"),
            flags("OpqCld (tenths)"),
            flags("Hvis (m)"),
            flags("CeilHgt (m)"),
            flags("Pwat (cm)"),
            flags("AOD (unitless)"),
            "?9",  # snow depth
            "?9",  # days since last snowfall
        ]
        fields = [
            str(int(year)),
            str(int(month)),
            str(int(day)),
            str(int(hour)),
            "60",
            "".join(meteorological + solar + weather),
            value("Dry-bulb (C)", missing=MISSING["dry_bulb"]),
            value("Dew-point (C)", missing=MISSING["dew_point"]),
            value("RHum (%)", missing=MISSING["relative_humidity"]),
            value("Pressure (mbar)", 100.0, MISSING["pressure"]),
            value("ETR (W/m^2)"),
            value("ETRN (W/m^2)"),
            MISSING["radiation"],  # horizontal infrared radiation: not in TMY3
            value("GHI (W/m^2)", missing=MISSING["radiation"]),
            value("DNI (W/m^2)", missing=MISSING["radiation"]),
            value("DHI (W/m^2)", missing=MISSING["radiation"]),
            value("GH illum (lx)", 100.0, MISSING["illuminance"]),
            value("DN illum (lx)", 100.0, MISSING["illuminance"]),
            value("DH illum (lx)", 100.0, MISSING["illuminance"]),
            value("Zenith lum (cd/m^2)", 10.0, MISSING["zenith_luminance"]),
            value("Wdir (degrees)", missing=MISSING["wind_direction"]),
            value("Wspd (m/s)", missing=MISSING["wind_speed"]),
            value("TotCld (tenths)", missing=MISSING["sky_cover"]),
            value("OpqCld (tenths)", missing=MISSING["sky_cover"]),
            value("Hvis (m)", 0.001, MISSING["visibility"]),
            value("CeilHgt (m)", missing=MISSING["ceiling_height"]),
            "9",  # present weather observation: TMY3's METAR codes are not EPW's
            "999999999",  # present weather codes
            value("Pwat (cm)", 10.0, MISSING["precipitable_water"]),
            value("AOD (unitless)", missing=MISSING["aerosol_optical_depth"]),
            MISSING["snow_depth"],
            MISSING["days_since_snow"],
            value("Alb (unitless)", missing=MISSING["albedo"]),
            value("Lprecip depth (mm)"),
            value("Lprecip quantity (hr)"),
        ]
        # The precipitation pair shares one flag, after both values.
        if row[column["Lprecip quantity (hr)"] + 1] == "?":
            fields[33], fields[34] = MISSING["precipitation_depth"], MISSING["precipitation_quantity"]
        assert len(fields) == 35
        lines.append(",".join(fields))
    return lines


def main():
    if len(sys.argv) != 3:
        sys.exit(f"usage: {sys.argv[0]} TMY3.CSV OUT.epw")
    source, out = sys.argv[1], sys.argv[2]
    with open(source, newline="", encoding="utf-8-sig") as f:
        rows = list(csv.reader(f))
    if len(rows) < 3 or not rows[1] or not rows[1][0].startswith("Date (MM/DD/YYYY)"):
        sys.exit(f"{source}: not a TMY3 CSV (its second line starts with `Date (MM/DD/YYYY)`)")
    name = source.replace("\\", "/").rsplit("/", 1)[-1]
    lines = convert(rows, name)
    with open(out, "w", newline="\n", encoding="utf-8") as f:
        f.write("\n".join(lines) + "\n")
    print(f"{out}: {len(lines) - 8} records", file=sys.stderr)


if __name__ == "__main__":
    main()
