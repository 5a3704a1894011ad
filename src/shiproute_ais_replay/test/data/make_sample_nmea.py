"""One-off: encode hand-chosen AIS field values (ITU-R M.1371 resolutions) into NMEA lines."""
from functools import reduce
from pathlib import Path

from pyais import encode_dict

T0 = 1_700_000_000  # 2023-11-14T22:13:20Z
A = 211001234
B = 366123456



def cs(s):
    return reduce(lambda a, c: a ^ ord(c), s, 0)


def tag(t):
    body = f"c:{t}"
    return f"\\{body}*{cs(body):02X}\\"


def pos(t, typ, mmsi, lat, lon, sog, cog, hdg, status=0):
    return encode_dict({"type": typ, "mmsi": mmsi, "lat": lat, "lon": lon, "speed": sog,
                        "course": cog, "heading": hdg, "status": status, "second": t % 60},
                       radio_channel="A", talker_id="AI",
                       sentence_type="VDO" if mmsi == A else "VDM")[0]

lines = []
lines.append(tag(T0) + pos(T0, 1, A, 54.5, 10.0, 12.5, 90.0, 90))
st = encode_dict({"type": 5, "mmsi": A, "shipname": "SHIPROUTE TEST", "imo": 9123456,
                  "draught": 12.3, "callsign": "DABC", "ship_type": 70},
                 radio_channel="A", talker_id="AI", seq_id=1)
assert len(st) == 2
lines.append(tag(T0 + 30) + st[0])
lines.append(st[1])
lines.append(tag(T0 + 60) + pos(T0 + 60, 1, A, 54.5, 10.006, 12.5, 90.0, 90))
bad = pos(T0 + 90, 1, A, 54.5, 10.009, 12.5, 90.0, 90)
good_cs = int(bad[-2:], 16)
lines.append(tag(T0 + 90) + bad[:-2] + f"{(good_cs ^ 0x01):02X}")  # wrong checksum
lines.append("this line is not an NMEA sentence at all")
lines.append(tag(T0 + 120) + pos(T0 + 120, 2, A, 54.5, 10.012, 12.5, 90.0, 90))
lines.append(tag(T0 + 180) + pos(T0 + 180, 3, A, 54.5, 10.018, 12.5, 90.0, 511))
lines.append(tag(T0 + 240) + pos(T0 + 240, 1, A, 91.0, 181.0, 12.5, 90.0, 90))
lines.append(tag(T0 + 300) + pos(T0 + 300, 1, A, 54.5, 11.0, 12.5, 90.0, 90))
lines.append(tag(T0 + 360) + pos(T0 + 360, 1, A, 54.5, 10.036, 102.3, 90.0, 90))
lines.append("2023-11-14T22:14:20Z " + pos(T0 + 60, 1, B, 33.7, -118.25, 0.0, 360.0, 511, 5))
lines.append(f"{T0 + 120}," + pos(T0 + 120, 1, B, 33.7, -118.25, 0.0, 360.0, 511, 5))
st2 = encode_dict({"type": 5, "mmsi": B, "shipname": "ORPHAN", "draught": 9.0},
                  radio_channel="B", talker_id="AI", sentence_type="VDM", seq_id=2)
lines.append(tag(T0 + 130) + st2[0])  # second part never arrives
lines.append(pos(T0 + 140, 1, B, 33.7, -118.25, 0.0, 360.0, 511, 5))  # no timestamp
out = Path(__file__).with_name("sample_ais.nmea")
out.write_text("\n".join(lines) + "\n")
print("\n".join(lines))
