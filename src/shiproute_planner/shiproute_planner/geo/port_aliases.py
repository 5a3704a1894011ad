"""Port names people type that the searoute gazetteer spells otherwise, and ports up rivers
or channels narrower than the coastline data, which voyages leave and reach at sea.

River ports (and ports behind an archipelago fairway narrower than the finest passage grid):
the position is the seaward end of the river or channel (the pilot boarding
area off its mouth, approximate positions read from small-scale charts, about 1 NM), where
the planned passage begins; the river passage itself is pilotage and is not planned.
"""

from __future__ import annotations

# common English, local or historical name -> name in searoute's ports.geojson (lower case)
ALIASES: dict[str, str] = {
    "busan": "pusan",
    "kolkata": "calcutta",
    "rangoon": "yangon",
    "bombay": "mumbai",
    "saigon": "ho chi minh city",
    "los angeles-long beach": "long beach",
    "new york city": "new york",
    "nyc": "new york",
    "gdańsk": "gdansk",
    "hong kong sar": "hong kong",
    "lisbon": "lisboa",
    "genoa": "genova",
    "naples": "napoli",
    "antwerp": "antwerpen",
    "anvers": "antwerpen",
    "gothenburg": "gotthenburg",
    "göteborg": "gotthenburg",
    "goteborg": "gotthenburg",
    "bermuda": "hamilton",
    "hamilton, bermuda": "hamilton",
    "leghorn": "livorno",
    "copenhagen": "kobenhavn",
    "algiers": "alger",
    "marseilles": "marseille",
    "athens": "piraeus",
    "oporto": "leixoes",
    "nantes": "montoir de bretagne",  # Nantes-Saint-Nazaire's terminals at the Loire mouth
    "saint-nazaire": "montoir de bretagne",
    "st nazaire": "montoir de bretagne",
    "nantes saint-nazaire": "montoir de bretagne",
    "gqeberha": "port elizabeth",
    "vizag": "vishakhapatnam",
    "visakhapatnam": "vishakhapatnam",
    "canton": "guangzhou",
    "amoy": "xiamen",
    "tientsin": "tianjin",
    "batavia": "jakarta",
    "smyrna": "izmir",
    "salonica": "thessaloniki",
    "salonika": "thessaloniki",
    "constantinople": "istanbul",
    "flushing": "vlissingen",
    "bruges": "zeebgrugge",
    "lourenco marques": "maputo",
    "lima": "callao",
    "glasgow": "greenock",  # the Clyde's deep-water port
    # the gazetteer's spellings and qualified names that a typed name does not reach
    "dunkirk": "dunkerque",  # the gazetteer's "Dunkirk" is Dunkirk, New York, on Lake Erie
    "dunkirk, france": "dunkerque",
    "zeebrugge": "zeebgrugge",
    "alesund": "aalesund",
    "makassar": "macassar",
    "ujung pandang": "macassar",
    "rijeka": "rijeka bakar",
    "kristiansand": "kristiansand s.chris",
}


# (gazetteer name, its UN/LOCODE) -> the right UN/LOCODE: the gazetteer's main "Portland" lies
# on the Columbia River at Portland, Oregon (USPDX) but carries Portland, Maine's code, which
# its "Portland (Me)" entry also has
LOCODE_FIXES: dict[tuple[str, str], str] = {
    ("portland", "USPWM"): "USPDX",
}


# UN/LOCODE -> (river or channel, seaward end lat, lon [deg])
RIVER_PORTS: dict[str, tuple[str, float, float]] = {
    "USHOU": ("Houston Ship Channel (Galveston Bay entrance, Bolivar Roads)", 29.30, -94.65),
    "DEHAM": ("Elbe (mouth, Elbe approach west of Cuxhaven)", 53.98, 8.25),
    "BEANR": ("Scheldt (Westerschelde mouth off Vlissingen)", 51.42, 3.40),
    "CAMTR": ("St Lawrence (pilot station off Les Escoumins)", 48.30, -69.35),
    "CAQUE": ("St Lawrence (pilot station off Les Escoumins)", 48.30, -69.35),
    "NLRTM": ("Nieuwe Waterweg / Maasmond (entrance off Hoek van Holland)", 51.99, 3.95),
    "DEBRE": ("Weser (mouth, off Bremerhaven approach)", 53.86, 8.05),
    "GBLON": ("Thames (estuary, Sunk pilot area)", 51.85, 1.60),
    "USMSY": ("Mississippi (Southwest Pass entrance)", 28.87, -89.45),
    # up the same river (~125 NM above New Orleans); the sea-lane network's nearest node to
    # it lies in Lake Pontchartrain, which no deep-sea ship reaches
    "USBTR": ("Mississippi (Southwest Pass entrance)", 28.87, -89.45),
    "USPHL": ("Delaware Bay (entrance, Cape Henlopen pilot area)", 38.78, -75.02),
    "USPDX": ("Columbia River (bar pilot boarding area off the entrance)", 46.22, -124.18),
    "FRURO": ("Seine (estuary, pilot boarding area off Le Havre)", 49.47, -0.02),
    "INCCU": ("Hooghly (Sandheads pilot station)", 20.88, 88.18),
    "ESSVQ": ("Guadalquivir (mouth, off Chipiona)", 36.78, -6.47),
    "GBMNC": ("Manchester Ship Canal and the Mersey (Mersey Bar)", 53.53, -3.30),
    "VNSGN": ("Saigon River (Long Tau channel, pilot boarding off Vung Tau)", 10.28, 107.05),
    "MMRGN": ("Yangon River (bar south of Elephant Point, pilot boarding area)", 16.35, 96.30),
    "BDCGP": ("Karnaphuli River (mouth, pilot boarding off Patenga)", 22.18, 91.77),
    "CNCAN": ("Pearl River (Lingding Yang off Nansha, below the Humen narrows)", 22.60, 113.68),
    # an archipelago fairway narrower than the finest passage grid (0.1 NM: Oxdjupet is
    # ~150 m wide), under compulsory pilotage
    "SESTO": ("Stockholm archipelago fairway (Sandhamn approach, pilot boarding area)",
              59.20, 19.05),
}
