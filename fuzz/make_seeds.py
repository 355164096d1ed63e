#!/usr/bin/env python3
"""Writes the small generated seeds of fuzz/corpus/<target>/ and the hand-made regression inputs of
tests/data/fuzz-regressions/<target>/ (the inputs issue 20 reported). Standard library only, so
binary formats (EXR, PNG, TIFF, APT) are written field by field; run from anywhere:
    python3 fuzz/make_seeds.py
"""
import json
import pathlib
import struct
import zlib

ROOT = pathlib.Path(__file__).resolve().parent.parent
CORPUS = ROOT / "fuzz" / "corpus"
REGRESSIONS = ROOT / "tests" / "data" / "fuzz-regressions"


def put(base, target, name, data):
    d = base / target
    d.mkdir(parents=True, exist_ok=True)
    (d / name).write_bytes(data if isinstance(data, bytes) else data.encode())


def exr_header_only(width, height, lines_per_chunk=16):
    """A ZIP-compressed scan-line OpenEXR header and a complete offset table, but no pixel data: a
    header that declares far more pixels than the file can hold."""
    return exr(1, 1, declared=(width, height), compression=3,
               chunks_only=(height + lines_per_chunk - 1) // lines_per_chunk)


def exr(width, height, channels=("counts",), attributes=(), declared=None, compression=0, chunks_only=None):
    """Uncompressed scan-line OpenEXR, FLOAT channels; `declared` overrides the data window."""
    def attr(name, kind, value):
        return name.encode() + b"\0" + kind.encode() + b"\0" + struct.pack("<i", len(value)) + value
    chlist = b"".join(c.encode() + b"\0" + struct.pack("<iB3xii", 2, 0, 1, 1) for c in sorted(channels)) + b"\0"
    dw = declared or (width, height)
    box = struct.pack("<iiii", 0, 0, dw[0] - 1, dw[1] - 1)
    header = (attr("channels", "chlist", chlist) + attr("compression", "compression", bytes([compression]))
              + attr("dataWindow", "box2i", box) + attr("displayWindow", "box2i", box)
              + attr("lineOrder", "lineOrder", b"\0") + attr("pixelAspectRatio", "float", struct.pack("<f", 1))
              + attr("screenWindowCenter", "v2f", struct.pack("<ff", 0, 0))
              + attr("screenWindowWidth", "float", struct.pack("<f", 1)))
    for name, kind, value in attributes:
        header += attr(name, kind, value)
    header += b"\0"
    if chunks_only:
        start = 8 + len(header) + 8 * chunks_only
        return b"\x76\x2f\x31\x01" + struct.pack("<I", 2) + header + struct.pack("<Q", start) * chunks_only
    start = 8 + len(header) + 8 * height
    line = 8 + 4 * width * len(channels)
    offsets = b"".join(struct.pack("<Q", start + y * line) for y in range(height))
    body = b""
    for y in range(height):
        pixels = b"".join(struct.pack("<f", 1000.0 + 10 * y + x) for _ in channels for x in range(width))
        body += struct.pack("<ii", y, len(pixels)) + pixels
    return b"\x76\x2f\x31\x01" + struct.pack("<I", 2) + header + offsets + body


def png(width, height, bit_depth=16):
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    bpp = bit_depth // 8
    rows = b"".join(b"\0" + b"".join((18000 + x + 100 * y).to_bytes(bpp, "big") if bpp == 2 else bytes([x + y])
                                     for x in range(width)) for y in range(height))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, bit_depth, 0, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b""))


def tiff(width, height, bits=16):
    """Little-endian uncompressed grey TIFF, one strip."""
    pixels = b"".join(struct.pack("<H", 18000 + x + 100 * y) for y in range(height) for x in range(width))
    entries = [(256, 3, 1, width), (257, 3, 1, height), (258, 3, 1, bits), (259, 3, 1, 1), (262, 3, 1, 1),
               (273, 4, 1, 8), (277, 3, 1, 1), (278, 3, 1, height), (279, 4, 1, len(pixels))]
    ifd = struct.pack("<H", len(entries)) + b"".join(
        struct.pack("<HHI", tag, kind, count) + (struct.pack("<HH", value, 0) if kind == 3 else struct.pack("<I", value))
        for tag, kind, count, value in entries) + struct.pack("<I", 0)
    return b"II*\0" + struct.pack("<I", 8 + len(pixels)) + pixels + ifd


def apt(msg_id, data=None, p1=0, p2=0, dest=0x01, source=0x50):
    if data is None:
        return struct.pack("<HBBBB", msg_id, p1, p2, dest, source)
    return struct.pack("<HHBB", msg_id, len(data), dest | 0x80, source) + data


def session(camera_serial="A655-1234", records=()):
    return json.dumps({
        "schema": "tirpol.session", "schema_version": 1, "created_utc": "2026-01-12T22:10:00Z",
        "camera": {"uri": "sim://synthetic", "vendor": "tirpol", "model": "sim", "serial": camera_serial,
                   "pixel_format": "Mono16", "width": 4, "height": 3, "bits_per_pixel": 16,
                   "frame_rate_hz": 30.0, "planck_constants": {}},
        "stage": {"uri": "sim://", "vendor": "tirpol", "model": "sim", "serial": "1", "firmware": "1",
                  "counts_per_degree": 1919.64},
        "plan": {"angles_deg": [0, 45, 90, 135], "frames_per_angle": 4},
        "metadata": {"site": "roof"}, "records": list(records), "complete": False}, indent=1)


def main():
    # --- seeds ---
    put(CORPUS, "exr", "counts_4x3.exr", exr(4, 3, ("counts", "counts_std"),
        [("camera_serial", "string", b"A655-1234"), ("polarizer_angle_deg", "double", struct.pack("<d", 45.0))]))
    put(CORPUS, "exr", "stokes_2x2.exr", exr(2, 2, ("S0", "S1", "S2")))
    put(CORPUS, "raw_image", "counts_16bit.png", png(4, 3))
    put(CORPUS, "raw_image", "counts_16bit.tif", tiff(4, 3))
    put(CORPUS, "session_json", "empty_session.json", session())
    put(CORPUS, "fit_csv", "extract_emissivity.csv",
        "name,view_angle_deg,temperature_k,pixels,l_dw_w_m2_sr,l_bb_w_m2_sr,eps_s0,eps_s0_2sigma,eps_s1,"
        "eps_s1_2sigma,eps_s2,eps_s2_2sigma\n"
        "panel_10,10,300,400,5,30,0.95,0.01,-0.002,0.002,0,0.002\n"
        "panel_45,45,300,400,5,30,0.93,0.01,-0.02,0.003,0,0.002\n"
        "panel_70,70,300,400,5,30,0.85,0.01,-0.08,0.004,0,0.002\n")
    put(CORPUS, "fit_csv", "hand_written.csv",
        "# angle, emissivity, 1 sigma\nangle_deg,e_s0,e_s0_sigma,e_s1,e_s1_sigma,wavelength_um\n"
        "0,0.96,0.005,0,0.002,10\n60,0.9,0.005,-0.05,0.002,10\n60,0.91,0.005,-0.04,0.002,4\n")
    put(CORPUS, "rsr_csv", "rsr.csv", "# flat LWIR\nwavelength_um,response\n7.5,0\n8,1\n14,1\n14.5,0\n")
    put(CORPUS, "roi_yaml", "regions.yaml",
        "regions:\n  - name: panel\n    polygon: [[1, 1], [20, 1], [20, 15], [1, 15]]\n"
        "  - name: sky\n    polygon: [[30, 0], [60, 0], [60, 10]]\nbackground: sky\n")
    put(CORPUS, "capture_plan", "plan.yaml",
        "angles_deg: [0, 45, 90, 135]\nframes_per_angle: 16\nsettle_s: 0.5\nrepeats: 2\n"
        "references:\n  - kind: blackbody\n    temperatures_k: [293.15, 313.15]\n    frames: 32\n"
        "  - kind: shutter\n    frames: 16\nmetadata: {site: roof, polarizer_tilt_deg: 5}\n")
    put(CORPUS, "apt_reply", "hw_info_and_status.bin",
        apt(0x0006, struct.pack("<I8sHBBBB48s12sHHH", 55123456, b"K10CR1\0\0", 16, 4, 0, 3, 0, b"rotation", b"", 1, 0, 1))
        + apt(0x0464, struct.pack("<HiHhI", 1, 136533, 0, 0, 0x400)) + apt(0x0444, p1=1))
    put(CORPUS, "apt_reply", "rich_response.bin", apt(0x0081, struct.pack("<HH64s", 0x0453, 2, b"limit switch")))
    put(CORPUS, "elliptec_reply", "replies.txt",
        "0IN0E1140028420211701016800023000\r\n0GS00\r\n0PO00008000\r\n0GS09\r\n")
    put(CORPUS, "refractive_index", "tabulated.csv", "# test\nwavelength_um,n,k\n8,1.5,0.01\n10,1.4,0.05\n12,1.3,0.2\n")
    put(CORPUS, "thermal_yaml", "minimal.yaml", "site: {latitude_deg: 43.1, longitude_deg: -77.6}\n")

    # --- regressions: the inputs of issue 20, each must give a clean tirpol::Error ---
    put(REGRESSIONS, "exr", "declares_40000x40000.exr", exr(4, 3, declared=(40000, 40000)))
    put(REGRESSIONS, "exr", "declares_4000x4000_in_tiny_file.exr", exr_header_only(4000, 4000))
    put(REGRESSIONS, "exr", "non_utf8_attribute.exr", exr(2, 2, attributes=[("note", "string", b"caf\xe9 \xff\xfe")]))
    put(REGRESSIONS, "raw_image", "eight_bit.png", png(4, 3, bit_depth=8))
    put(REGRESSIONS, "raw_image", "png_declares_40000x40000.png", png(4, 3)[:16] + struct.pack(">II", 40000, 40000) + png(4, 3)[24:])
    put(REGRESSIONS, "raw_image", "tiff_bits_per_sample_8.tif", tiff(4, 3, bits=8))
    put(REGRESSIONS, "fit_csv", "emissivity_1e308.csv", "angle_deg,e_s0,e_s0_sigma,e_s1,e_s1_sigma\n10,1e308,0.01,0,0.01\n")
    put(REGRESSIONS, "fit_csv", "emissivity_5.csv", "angle_deg,e_s0,e_s0_sigma,e_s1,e_s1_sigma\n10,5,0.01,0,0.01\n")
    put(REGRESSIONS, "rsr_csv", "response_1e308.csv", "wavelength_um,response\n8,1\n10,1e308\n14,1\n")
    put(REGRESSIONS, "roi_yaml", "non_utf8_name.yaml", b"regions:\n  - name: \"pan\xe9l\"\n    polygon: [[1, 1], [5, 1], [5, 5]]\n")
    put(REGRESSIONS, "roi_yaml", "duplicate_key.yaml", "regions:\n  - name: a\n    name: b\n    polygon: [[1, 1], [5, 1], [5, 5]]\n")
    put(REGRESSIONS, "capture_plan", "settle_2_pow_32.yaml", "settle_s: 4294967296\nframes_per_angle: 0x7fffffff\n")
    put(REGRESSIONS, "capture_plan", "yaml_bomb.yaml",
        "a: &a [x, x, x, x, x, x, x, x, x]\nb: &b [*a, *a, *a, *a, *a, *a, *a, *a, *a]\nc: &c [*b, *b, *b, *b, *b, *b, *b, *b, *b]\n"
        "d: &d [*c, *c, *c, *c, *c, *c, *c, *c, *c]\ne: &e [*d, *d, *d, *d, *d, *d, *d, *d, *d]\n"
        "metadata: {f: [*e, *e, *e, *e, *e, *e, *e, *e, *e]}\n")
    put(REGRESSIONS, "scene_yaml", "temperature_1e9_celsius.yaml",
        "band: {lo_um: 8, hi_um: 14}\ncamera: {resolution: [8, 6], fov_deg: 30, position: [0, -6, 1.6], look_at: [0, 0, 1]}\n"
        "sky: {type: uniform, temperature: \"1e9 °C\"}\n"
        "objects:\n  - {name: ball, geometry: {type: sphere, radius: 0.5}, material: {model: lambertian, emissivity: 0.9}, "
        "temperature: \"1e9 °C\"}\n")
    put(REGRESSIONS, "thermal_yaml", "duplicate_site.yaml",
        "site: {latitude_deg: 43.1, longitude_deg: -77.6}\nsite: {latitude_deg: 0, longitude_deg: 0}\n")
    put(REGRESSIONS, "session_json", "non_utf8_serial.json",
        session(camera_serial="x").replace('"serial": "x"', '"serial": "\\udcff"'))
    put(REGRESSIONS, "apt_reply", "length_beyond_limit.bin", struct.pack("<HHBB", 0x0006, 0xFFFF, 0x81, 0x50) + b"\0" * 8)
    put(REGRESSIONS, "elliptec_reply", "short_info.txt", "0IN0E\r\nFGSzz\r\n0PO-8000000\r\n")


if __name__ == "__main__":
    main()
