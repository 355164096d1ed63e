#!/usr/bin/env python3
"""Writes the small generated seeds of fuzz/corpus/<target>/ and the hand-made regression inputs of
tests/data/fuzz-regressions/<target>/ (the inputs that once crashed or misled tirpol). Standard library only, so
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


def png_chunk(kind, data, crc=None):
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) if crc is None else crc)


def png(width, height, bit_depth=16, ancillary=b""):
    """Grey PNG of counts 18000 + x + 100 y; `ancillary` chunks go right after IHDR."""
    chunk = png_chunk
    bpp = bit_depth // 8
    rows = b"".join(b"\0" + b"".join((18000 + x + 100 * y).to_bytes(bpp, "big") if bpp == 2 else bytes([x + y])
                                     for x in range(width)) for y in range(height))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, bit_depth, 0, 0, 0, 0))
            + ancillary + chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b""))


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
    put(CORPUS, "capture_plan", "drift_plan.yaml",
        "angles_deg: [0, 45, 90, 135]\nframes_per_angle: 4\n"
        "scene_reference: {roi: {x: 2, y: 2, width: 6, height: 6}, temperature_c: 30, temperature_sigma_k: 0.02}\n"
        "shutter_interleave: {every: 4, temperature_k: 295.0, frames: 16}\n")
    put(CORPUS, "fluke_scpi", "replies.txt",
        "FLUKE,4180,B12345,1.10\r\n35.012\r\n+3.5012E+01\r\n0\r\n1\r\n0,\"No error\"\r\n"
        "-113,\"Undefined header\"\r\nSOURce:SPOint 35.0\nsour:stab:test?\n*IDN?\n")
    put(CORPUS, "live_request", "capture_start.txt",
        '42\ntirpol_token=abc; other=1\npage-1\n{"plan": "plan.yaml", "output": "session", "resume": true}')
    put(CORPUS, "live_request", "observation.txt", '0\n\nclient\n{"frames": 3, "ok": [1, 2]}')
    put(CORPUS, "sweep_yaml", "time_grid.yaml",
        "scene: thermal/ball_on_snow_day_predicted.yaml\nset:\n  camera.resolution: [32, 24]\n  sampling.spp: 4\n"
        "axes:\n  time: {from: 2026-01-16T06:00, to: 2026-01-16T12:00, step_h: 3}\n"
        "  materials.snow.parameters.sigma: [0.1, 0.3]\n")
    put(CORPUS, "sweep_yaml", "list_regions.yaml",
        "scene: scenes/ball_on_snow_night.yaml\ncombine: list\nseed: 7\n"
        "axes:\n  camera.position: [[0, -6, 1.6], [0, -8, 2]]\n  sampling.spp: [4, 8]\n"
        "regions:\n  rim: {object: ball, sectors_deg: [[0, 90]]}\n  patch: {polygon: [[1, 1], [9, 1], [9, 9]]}\n"
        "contrasts:\n  rim_vs_patch: {a: rim, b: patch}\n")
    put(CORPUS, "camera_geometry", "model.yaml",
        "%YAML:1.0\n---\nimage_width: 640\nimage_height: 480\ncamera_matrix: !!opencv-matrix\n"
        "   rows: 3\n   cols: 3\n   dt: d\n   data: [ 800., 0., 319.5, 0., 800., 239.5, 0., 0., 1. ]\n"
        "distortion_coefficients: !!opencv-matrix\n   rows: 1\n   cols: 5\n   dt: d\n"
        "   data: [ -0.1, 0.01, 0., 0., 0. ]\n")
    put(CORPUS, "camera_geometry", "pose.yaml",
        "%YAML:1.0\n---\nrotation_camera_from_world: !!opencv-matrix\n   rows: 3\n   cols: 3\n   dt: d\n"
        "   data: [ 1., 0., 0., 0., 0., -1., 0., 1., 0. ]\ntranslation_m: !!opencv-matrix\n   rows: 3\n   cols: 1\n"
        "   dt: d\n   data: [ 0., 1.6, 6. ]\n")
    put(CORPUS, "control_points", "survey.csv",
        "# survey\nname,x_m,y_m,z_m,u_px,v_px\na,1,2,3,100.5,200.25\nb,0,0,5,320,240\n")
    put(CORPUS, "control_points", "pairs.yaml",
        "- {measured: [1, 2], simulated: [3.5, 4]}\n- measured: [10, 20]\n  simulated: [11, 22]\n")
    put(CORPUS, "weather_csv", "field_log.csv",
        "time,air_temperature_c,relative_humidity_pct,wind_speed_m_s,global_horizontal_w_m2\n"
        "2026-01-16T00:00,-5,80,2,0\n2026-01-16T01:00-07:00,-6,82,1.5,0\n2026-01-16T09:00Z,-7,85,1,0\n")

    # --- regressions: inputs that once crashed or misled tirpol, each must give a clean tirpol::Error ---
    put(REGRESSIONS, "exr", "declares_40000x40000.exr", exr(4, 3, declared=(40000, 40000)))
    put(REGRESSIONS, "exr", "declares_4000x4000_in_tiny_file.exr", exr_header_only(4000, 4000))
    put(REGRESSIONS, "exr", "non_utf8_attribute.exr", exr(2, 2, attributes=[("note", "string", b"caf\xe9 \xff\xfe")]))
    # An attribute of a type OpenEXR does not know, declaring 1.6 GB in a 400-byte file: OpenEXR
    # allocated the declared size before reading (what made the exr fuzz target run 3 inputs/s).
    opaque = exr(2, 2, attributes=[("junk", "mystery", b"abcd")])
    put(REGRESSIONS, "exr", "attribute_declares_1_6_GB.exr",
        opaque.replace(b"junk\0mystery\0" + struct.pack("<i", 4), b"junk\0mystery\0" + struct.pack("<i", 0x61686300)))
    # Uncompressed with a complete offset table but no pixels: 16 KB declared in < 1 KB (passed the
    # general 4096:1 bound, meant only for PIZ/DWA).
    put(REGRESSIONS, "exr", "uncompressed_declares_64x64_without_pixels.exr",
        exr(1, 1, declared=(64, 64), compression=0, chunks_only=64))
    put(REGRESSIONS, "raw_image", "eight_bit.png", png(4, 3, bit_depth=8))
    # Found by the camera_geometry target: OpenCV allocated a 3 × 2^31 matrix for a `cols:` that is not a number.
    put(REGRESSIONS, "camera_geometry", "matrix_cols_not_a_number.yaml",
        b"%YAML:1.0\n---\nimage_width: 640\nimage_height: 480\ncamera_matrix: !!opencv-matrix\n   rows: 3\n"
        b"   cols: \xd5\n   dt: d\n   data: [ 800., 0., 319.5, 0., 800., 239.5, 0., 0., 1. ]\n")
    # ... and OpenCV asserted (cv::Exception) when a matrix field was a list rather than a mapping.
    put(REGRESSIONS, "camera_geometry", "matrix_field_is_a_list.yaml",
        "%YAML:1.0\n---\nrotation_camera_from_world: !!opencv-matrix\n   rows: 3\n   cols: 3\n   dt: d\n"
        "   data: [ 1., 0., 0., 0., 0., -1., 0., 1., 0. ]\ntranslation_m: !!opencv-matrix\n  , 1.6, 6. ]\n")
    # ... and OpenCV's YAML parser threw std::length_error on this text.
    put(REGRESSIONS, "camera_geometry", "parser_length_error.yaml",
        "%YAML:1.0\n---\nimage_width: 640\nimage_height: 480\ncamera_matrix: !!opencv-matrixmatrix\n   rows: 1\n"
        "   cols: 5\n   dt: d\n   dataimage_width: 640\nimage_height: 480\ncamera_matrix: !!opencv-matrixmatrix\n"
        "   rows: 1\n   cols: 5\n   : [ -0.1, 0.01, 0., 0., 0. ]\n")
    # Chunks that cannot change a count but made libpng (under OpenCV) print warnings on stderr: a text
    # chunk with a wrong CRC and a colour profile that is not zlib data.
    put(REGRESSIONS, "raw_image", "ancillary_chunk_warnings.png",
        png(4, 3, ancillary=png_chunk(b"tEXt", b"Comment\0camera raw", crc=0) + png_chunk(b"iCCP", b"x\0\0not zlib")))
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
