#!/usr/bin/env python3
"""vkhr beside strandbench, interleaved in rounds, written as data for the docs' results store.

Run through scripts/peer-vkhr.sh VKHR_SRC [options], which builds vkhr and passes --vkhr,
--vkhr-root, --vkhr-commit and --work. For each row (a frame size and a vkhr strand mode) it
writes a vkhr scene with strandbench's fitted camera and light for the strand file (the same
eye, target and field of view are given to strandbench explicitly), then each round runs
vkhr's --benchmark mode (Vulkan timestamps per pass, the mean of its last --frames frames) and
strandbench's matching render (the median of --repeat frames), alternating which goes first.
Ratios strandbench/vkhr are taken within a round and summarised with a 95% interval
(scripts/paired-compare.py's ratio_interval). Afterwards each row's images are scored against
strandbench's exact reference of the same view (strandbench compare).
"""
import argparse, array, datetime, glob, importlib.util, json, math, os, shutil
import struct, subprocess, sys, tempfile, zlib

sys.dont_write_bytecode = True  # no __pycache__ in scripts/ from loading paired-compare.py
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SB = os.path.join(ROOT, "build", "strandbench")
_spec = importlib.util.spec_from_file_location("paired_compare", os.path.join(ROOT, "scripts", "paired-compare.py"))
pc = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(pc)

FOV = 35.0                   # strandbench's default vertical field of view (scenes/view.h)
LIGHT_DIR = (-1.0, -1.2, -0.8)  # strandbench's default direction of light travel (scenes/view.cpp)
# vkhr's passes (its benchmark CSV) against strandbench's: one line of the per-pass table each.
VKHR_PASSES = ["Bake Shadow Maps", "Voxelize Strands", "Clear PPLL Nodes", "Draw Hair Styles",
               "Raymarch Strands", "Resolve the PPLL"]


def fail(msg):
    print(f"peer-vkhr: {msg}", file=sys.stderr)
    sys.exit(2)


def read_hair(path):
    """A HAIR file (strandbench's and vkhr's format): its header fields and its points turned
    z-up to y-up as strandbench's file scene does (up=auto for .hair: (x, y, z) -> (x, z, -y))."""
    with open(path, "rb") as f:
        data = f.read()
    if len(data) < 128 or data[:4] != b"HAIR":
        fail(f"{path}: not a HAIR file")
    n_strands, n_points, flags = struct.unpack_from("<III", data, 4)
    thickness, transparency = struct.unpack_from("<ff", data, 20)
    if not flags & 2:
        fail(f"{path}: no points array")
    off = 128 + (2 * n_strands if flags & 1 else 0)
    if len(data) < off + 12 * n_points:
        fail(f"{path}: shorter than its header says")
    pts = array.array("f")
    pts.frombytes(data[off:off + 12 * n_points])
    if sys.byteorder != "little":
        pts.byteswap()
    turned = array.array("f", [0.0]) * len(pts)
    turned[0::3], turned[1::3] = pts[0::3], pts[2::3]
    turned[2::3] = array.array("f", (-y for y in pts[1::3]))
    lo = [min(turned[i::3]) for i in range(3)]
    hi = [max(turned[i::3]) for i in range(3)]
    return dict(data=data, strands=n_strands, points=n_points, flags=flags, thickness=thickness,
                transparency=transparency, lo=lo, hi=hi, offset=off, turned=turned)


def fit_camera(hair, w, h):
    """strandbench's fitCamera for a file scene (scenes/view.cpp, byBox: the box's front face
    just inside the frame), the eye on +z of the bounds' centre."""
    lo, hi = hair["lo"], hair["hi"]
    c = [(a + b) / 2 for a, b in zip(lo, hi)]
    r = math.dist(lo, hi) / 2
    half_y = math.radians(FOV) / 2
    half_x = math.atan(math.tan(half_y) * w / h)
    hb = [max(0.5 * (b - a), 1e-4 * r) for a, b in zip(lo, hi)]
    dist = hb[2] + 1.04 * max(hb[0] / math.tan(half_x), hb[1] / math.tan(half_y))
    return c, [c[0], c[1], c[2] + dist], dist


def vec(v):
    return ",".join(f"{x:.6g}" for x in v)


def write_scene(folder, hair, w, h, thickness, alpha):
    """A vkhr scene and its strand file: the camera and light strandbench fits; the strand file
    a copy with the points turned y-up as strandbench turns them, the default thickness set
    (vkhr's strand width in pixels: 1.0 draws 1-pixel strands; None keeps the file's) and the
    default transparency set to alpha: vkhr uses that field as the hair's opacity (in colour and
    in its deep shadows), strandbench takes alpha= and shadow_alpha= of the scene."""
    os.makedirs(folder, exist_ok=True)
    data = bytearray(hair["data"])
    t = hair["thickness"] if thickness is None else thickness
    struct.pack_into("<ff", data, 20, t, alpha)
    turned = hair["turned"]
    if sys.byteorder != "little":
        turned = array.array("f", turned)
        turned.byteswap()
    data[hair["offset"]:hair["offset"] + 12 * hair["points"]] = turned.tobytes()
    with open(os.path.join(folder, "strands.hair"), "wb") as f:
        f.write(data)
    target, eye, dist = fit_camera(hair, w, h)
    scene = {
        "camera": {"fieldOfView": FOV, "lookAt": target, "origin": eye, "upward": [0, 1, 0]},
        # vkhr's "direction" points towards the light; strandbench's is the light's travel.
        "lights": [{"direction": [-x for x in LIGHT_DIR], "intensity": [1.0, 1.0, 1.0]}],
        "root": 0,
        "nodes": [{"children": [1]},
                  {"scale": [1, 1, 1], "translate": [0, 0, 0], "rotate": {"axis": [0, 1, 0], "angle": 0.0},
                   "name": "strands", "models": [], "styles": ["strands.hair"]}],
    }
    path = os.path.join(folder, "scene.vkhr")
    with open(path, "w") as f:
        json.dump(scene, f, indent=1)
    return path, target, eye, dist


def png_pixels(path):
    """(width, height, channels, bytes) of an 8-bit, non-interlaced PNG (vkhr's and strandbench's)."""
    with open(path, "rb") as f:
        d = f.read()
    pos, idat, w = 8, b"", 0
    while pos < len(d):
        n, kind = struct.unpack_from(">I4s", d, pos)
        body = d[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            w, h, depth, ctype, _, _, interlace = struct.unpack(">IIBBBBB", body)
            if depth != 8 or interlace or ctype not in (0, 2, 4, 6):
                raise ValueError(f"{path}: PNG kind not read here")
            ch = {0: 1, 2: 3, 4: 2, 6: 4}[ctype]
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    raw, stride, out, prev = zlib.decompress(idat), w * ch, bytearray(), bytearray(w * ch)
    for y in range(h):
        ftype, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - ch] if i >= ch else 0
            b, c = prev[i], (prev[i - ch] if i >= ch else 0)
            if ftype == 1: line[i] = (line[i] + a) & 255
            elif ftype == 2: line[i] = (line[i] + b) & 255
            elif ftype == 3: line[i] = (line[i] + (a + b) // 2) & 255
            elif ftype == 4:
                p = a + b - c
                pa, pb, pc_ = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc_ else b if pb <= pc_ else c)) & 255
        out += line
        prev = line
    return w, h, ch, bytes(out)


def covered_pixels(path):
    """Pixels not of the black background (both renderers clear to black)."""
    w, h, ch, px = png_pixels(path)
    rgb = min(ch, 3)
    return sum(1 for i in range(0, len(px), ch) if any(px[i:i + rgb]))


def run_vkhr(a, row, scene, rundir, steps=512):
    os.makedirs(rundir)
    os.symlink(os.path.join(a.vkhr_root, "share"), os.path.join(rundir, "share"))  # vkhr reads share/ from its cwd
    w, h = row["w"], row["h"]
    env = dict(os.environ, VKHR_SB_FRAMES=str(a.frames), VKHR_SB_SCENE=scene, VKHR_SB_WIDTH=str(w),
               VKHR_SB_HEIGHT=str(h), VKHR_SB_DISTANCE=f"{row['dist']:.6g}",
               VKHR_SB_RENDERER=row["vkhr_renderer"], VKHR_SB_STEPS=str(steps))
    cmd = ["xvfb-run", "-a", "-s", f"-screen 0 {max(w, 1280)}x{max(h, 1024)}x24", a.vkhr,
           "--width", str(w), "--height", str(h), "--benchmark", "yes", "--ui", "no", scene]
    try:
        res = subprocess.run(cmd, cwd=rundir, env=env, capture_output=True, text=True, timeout=a.timeout)
    except subprocess.TimeoutExpired:
        return {"error": f"vkhr ran past {a.timeout} s"}
    csvs = glob.glob(os.path.join(rundir, "benchmarks", "*.csv"))
    if res.returncode != 0 or not csvs:
        tail = (res.stderr.strip().splitlines() or ["no output"])[-1]
        return {"error": f"vkhr exit {res.returncode}: {tail}"}
    with open(csvs[0]) as f:
        lines = [l for l in f.read().splitlines() if l.strip()]
    head = [x.strip() for x in lines[0].split(",")]
    cells = [x.strip() for x in lines[1].split(",")]
    # The GPU's name may hold commas ("llvmpipe (LLVM 15.0.6, 256 bits)"): the columns before
    # it are read from the left, those after it from the right.
    g = head.index("GPU")
    after = len(head) - g - 1
    vals = dict(zip(head[:g], cells[:g]))
    vals["GPU"] = ",".join(cells[g:len(cells) - after])
    vals.update(zip(head[g + 1:], cells[len(cells) - after:]))
    shots = glob.glob(os.path.join(rundir, "benchmarks", "*", "0.png"))
    return {"frame": float(vals["Total Frame Time"]),
            "passes": {p: float(vals[p]) for p in VKHR_PASSES if float(vals.get(p, 0) or 0) > 0},
            "bytes": int(vals["Total Memory Use"]), "ppll_bytes": int(vals["PPLL"]),
            "geometry_bytes": int(vals["Geometry"]), "volume_bytes": int(vals["Volume"]),
            "gpu": vals["GPU"], "image": shots[0] if shots else None}


def sb_args(row, hair_path, alpha, extra=()):
    return (["--scene", f"file:path={hair_path},up=z,alpha={alpha:g},shadow_alpha={alpha:g}", "--shadow", row["sb_shadow"], "--oit", row["sb_oit"],
             "--primitive", row["sb_primitive"],
             "--backend", "vulkan", "--size", f"{row['w']}x{row['h']}",
             f"--camera-eye={vec(row['eye'])}", f"--camera-target={vec(row['target'])}",
             "--fov", f"{FOV:g}", f"--light-direction={vec(LIGHT_DIR)}"] + list(extra))


def run_sb(args):
    res = subprocess.run([SB, "render"] + args + ["--json"], capture_output=True, text=True)
    if res.returncode == 2:  # refused (bad input or a plan the device cannot hold): a row saying so
        return {"refused": (res.stderr.strip().splitlines() or ["exit 2"])[-1]}
    if res.returncode != 0:
        fail(f"strandbench render {' '.join(args)}: exit {res.returncode}\n{res.stderr}")
    d = json.loads(res.stdout)
    return {"frame": d["frame_ms"]["median"], "passes": {p["name"]: p["ms"]["median"] for p in d["passes"]},
            "bytes": d["memory"]["total_bytes"], "dc": d.get("depth_complexity", {}).get("eye"),
            "device": d.get("device"), "driver": d.get("driver"), "timing": d.get("timing")}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--vkhr", required=True, help="the built vkhr program")
    ap.add_argument("--vkhr-root", required=True, help="its source copy (share/ with compiled shaders)")
    ap.add_argument("--vkhr-commit", default="unknown")
    ap.add_argument("--work", required=True, help="scratch folder for scenes, runs and images")
    ap.add_argument("--hair", default=os.path.join(ROOT, "..", "shared", "models", "straight.hair"))
    ap.add_argument("--rounds", type=int, default=3, help="interleaved rounds (at least 2 for an interval)")
    ap.add_argument("--frames", type=int, default=2, help="vkhr: frames averaged (and as many warm-up)")
    ap.add_argument("--repeat", type=int, default=3, help="strandbench: timed frames (median)")
    ap.add_argument("--rows", default="matched:640x360,thin:640x360,matched:1280x720",
                    help="comma list of MODE:WxH, MODE matched (1-pixel strands), thin (vkhr as it ships) "
                         "or raymarch (vkhr's raymarcher beside strandbench's voxel + occupancy)")
    ap.add_argument("--shadow-size", type=int, default=1024, help="both: shadow map side (vkhr's is fixed at 1024)")
    ap.add_argument("--k", type=int, default=16, help="strandbench's kbuffer k (vkhr's resolve keeps 16)")
    ap.add_argument("--alpha", type=float, default=0.5,
                    help="hair opacity of both (vkhr: the file's default transparency field, which it "
                         "uses as opacity; strandbench: the scene's alpha= and shadow_alpha=)")
    ap.add_argument("--timeout", type=int, default=900, help="seconds per vkhr run")
    ap.add_argument("--json", default=os.environ.get("SB_DOCS_RESULTS", ""),
                    help="where to write the run's data (default $SB_DOCS_RESULTS, which "
                         "scripts/docs-record.sh sets; without either: printed)")
    a = ap.parse_args()
    if a.rounds < 1 or a.frames < 1 or a.repeat < 1:
        fail("--rounds, --frames and --repeat: at least 1")
    if not 0 < a.alpha <= 1:
        fail(f"--alpha {a.alpha}: in (0, 1]")
    if not os.path.isfile(a.hair):
        fail(f"--hair {a.hair}: no such file")
    hair = read_hair(a.hair)
    rows = []
    for spec in a.rows.split(","):
        try:
            mode, size = spec.split(":")
            w, h = (int(x) for x in size.split("x"))
        except ValueError:
            fail(f"--rows {spec}: want MODE:WIDTHxHEIGHT")
        if mode not in ("matched", "thin", "raymarch") or not (0 < w <= 4096 and 0 < h <= 4096):
            fail(f"--rows {spec}: MODE matched, thin or raymarch; sizes 1..4096")
        rows.append({"mode": mode, "w": w, "h": h, "name": f"{mode} {w}x{h}"})
    if a.frames < 1:
        fail("--frames: at least 1")
    shutil.rmtree(a.work, ignore_errors=True)
    os.makedirs(a.work)
    hair_abs = os.path.abspath(a.hair)
    for row in rows:
        folder = os.path.join(a.work, row["name"].replace(" ", "-"))
        row["scene"], row["target"], row["eye"], row["dist"] = write_scene(
            folder, hair, row["w"], row["h"], None if row["mode"] == "thin" else 1.0, a.alpha)
        row["vkhr_renderer"] = "raymarcher" if row["mode"] == "raymarch" else "rasterizer"
        if row["mode"] == "raymarch":
            # vkhr raymarches a 256^3 strand density volume: strandbench's voxel shadow at that
            # grid and its occupancy transparency are the nearest equivalents, not the same method.
            row["sb_shadow"], row["sb_oit"] = f"voxel:grid=256,size={a.shadow_size}", "occupancy"
        else:
            row["sb_shadow"] = f"adsm:size={a.shadow_size},kernel=3"
            row["sb_oit"] = f"kbuffer:k={a.k}"
        # Thin rows: strandbench's form of the peer's thin strands, the file's world widths drawn
        # by their coverage (--primitive world); its exact reference draws the same widths.
        row["sb_primitive"] = "world" if row["mode"] == "thin" else "lines"
        row.update(vk=[], sb=[], ratios=[], refused=None, vk_error=None)

    def sb_key(row):  # rows asking strandbench for the same render share its run of a round
        return (row["w"], row["h"], row["sb_shadow"], row["sb_oit"], row["sb_primitive"])

    started = datetime.datetime.now(datetime.timezone.utc)
    for r in range(a.rounds):
        sb_round = {}
        for row in rows:
            key = sb_key(row)
            order = ("vkhr", "sb") if r % 2 == 0 else ("sb", "vkhr")
            got = {}
            for who in order:
                if who == "vkhr":
                    got["vkhr"] = run_vkhr(a, row, row["scene"], os.path.join(a.work, f"round{r}-{row['name'].replace(' ', '-')}"))
                elif key in sb_round:
                    got["sb"] = sb_round[key]
                else:
                    got["sb"] = sb_round[key] = run_sb(sb_args(row, hair_abs, a.alpha, ["--repeat", str(a.repeat), "--warmup", "1"]))
            v, s = got["vkhr"], got["sb"]
            if "error" in v:
                row["vk_error"] = v["error"]
            else:
                row["vk"].append(v)
            if "refused" in s:
                row["refused"] = s["refused"]
            else:
                row["sb"].append(s)
            if "error" not in v and "refused" not in s:
                row["ratios"].append(s["frame"] / v["frame"])
            print(f"round {r + 1}/{a.rounds} {row['name']}: vkhr "
                  f"{v.get('frame', v.get('error'))} ms, strandbench {s.get('frame', s.get('refused'))} ms", flush=True)

    # Images: each row's last vkhr screenshot and strandbench's image against strandbench's exact
    # reference of the same view (not timed).
    for row in rows:
        row["score"] = None
        folder = os.path.dirname(row["scene"])
        ref, own = os.path.join(folder, "reference.png"), os.path.join(folder, "strandbench.png")
        res = run_sb(sb_args(row, hair_abs, a.alpha, ["--repeat", "1", "--reference", "--reference-out", ref, "--out", own]))
        if "refused" in res:
            row["score"] = {"refused": res["refused"]}
            continue
        score = {"sb_pixels": covered_pixels(own)}
        for who, img in (("vkhr", row["vk"][-1]["image"] if row["vk"] else None), ("sb", own)):
            if img is None:
                continue
            out = subprocess.run([SB, "compare", img, ref], capture_output=True, text=True)
            if out.returncode == 0:
                c = json.loads(out.stdout)
                score[who] = {"rmse": c.get("rmse"), "psnr": c.get("psnr"), "ssim": c.get("ssim"),
                              "flip": (c.get("flip") or {}).get("mean")}
            else:
                score[who] = {"error": (out.stderr.strip().splitlines() or ["?"])[-1]}
            if who == "vkhr":
                score["vkhr_pixels"] = covered_pixels(img)
                shutil.copy(img, os.path.join(folder, "vkhr.png"))
        row["score"] = score

    data = results_data(a, rows, hair, started)
    if a.json:
        write_json(a.json, data)
    else:
        print(json.dumps(data, indent=1))


def interval(values):
    """{mean, lo, hi, rounds} over rounds (lo and hi null with one round)."""
    m, lo, hi = pc.mean_interval(values)
    return {"mean": m, "lo": lo, "hi": hi, "rounds": len(values)}


def results_data(a, rows, hair, started):
    """The run as data for the results store (docs/results/peer-vkhr*/results.json): raw ms,
    bytes and counts; docs/results/peer-vkhr*/blocks.json formats them."""
    sb0 = next((s for row in rows for s in row["sb"]), {})
    vk0 = next((v for row in rows for v in row["vk"]), {})
    out = {"vkhr_commit": a.vkhr_commit, "started": f"{started:%Y-%m-%dT%H:%M:%SZ}",
           "device": sb0.get("device") or vk0.get("gpu"), "driver": sb0.get("driver"),
           "timing": sb0.get("timing"), "rounds": a.rounds, "frames": a.frames, "repeat": a.repeat,
           "hair": {"file": os.path.basename(a.hair), "strands": hair["strands"],
                    "segments": hair["points"] - hair["strands"], "thickness": hair["thickness"]},
           "vkhr_program": os.path.basename(a.vkhr), "rows": []}
    for row in rows:
        d = {"name": row["name"], "mode": row["mode"], "width": row["w"], "height": row["h"],
             "sb_shadow": row["sb_shadow"], "sb_oit": row["sb_oit"], "sb_primitive": row["sb_primitive"]}
        d[row["mode"]] = True  # a section per mode in the templates (no conditionals there)
        if row["vk"]:
            last = row["vk"][-1]
            d["vk"] = {"frame": interval([v["frame"] for v in row["vk"]]), "bytes": last["bytes"],
                       "ppll_bytes": last["ppll_bytes"], "geometry_bytes": last["geometry_bytes"],
                       "volume_bytes": last["volume_bytes"],
                       "passes": [{"name": p, **interval([v["passes"].get(p, 0.0) for v in row["vk"]])}
                                  for p in VKHR_PASSES if any(p in v["passes"] for v in row["vk"])],
                       "pass_sum": interval([sum(v["passes"].values()) for v in row["vk"]])}
        else:
            d["vk_failed"] = row["vk_error"]
        if row["sb"]:
            names = list(dict.fromkeys(p for s in row["sb"] for p in s["passes"]))
            d["sb"] = {"frame": interval([s["frame"] for s in row["sb"]]), "bytes": row["sb"][-1]["bytes"],
                       "passes": [{"name": p, **interval([s["passes"].get(p, 0.0) for s in row["sb"]])}
                                  for p in names],
                       "depth_complexity": row["sb"][-1].get("dc")}
        else:
            d["sb_refused"] = row["refused"]
        if row["ratios"]:
            g, lo, hi = pc.ratio_interval(row["ratios"])
            d["ratio"] = {"gmean": g, "lo": lo, "hi": hi, "rounds": len(row["ratios"])}
        sc = row["score"] or {}
        if "refused" in sc:
            d["score_refused"] = sc["refused"]
        else:
            d["score"] = {"vkhr_pixels": sc.get("vkhr_pixels"), "sb_pixels": sc.get("sb_pixels")}
            for who in ("vkhr", "sb"):
                x = sc.get(who)
                if x and "error" in x:
                    d["score"][who + "_failed"] = x["error"]
                elif x:
                    d["score"][who] = x
        out["rows"].append(d)
    return out


def write_json(path, data):
    """Written whole or not at all."""
    fd, tmp = tempfile.mkstemp(dir=os.path.dirname(os.path.abspath(path)), suffix=".tmp")
    with os.fdopen(fd, "w") as f:
        json.dump(data, f, indent=1)
        f.write("\n")
    os.replace(tmp, path)
    print(f"peer-vkhr: wrote {path}")


if __name__ == "__main__":
    main()
