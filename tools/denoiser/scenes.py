"""Random training views for the learned denoiser: procedural glTF scenes with materials
drawn over the whole material schema, built-in scenes and shared models under random
cameras, environments and lights (docs/LEARNED_DENOISER.md, "Training").

Everything is drawn from a numpy Generator, so a data set is reproducible from its seed.
"""
from __future__ import annotations

import base64
import json
import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

# Held out of training and reported separately (at least three environments and two
# models, the issue asks): the benchmark's suzi scenes are then held out too.
HELD_OUT_ENVS = ("hall", "forest", "city")
HELD_OUT_MODELS = ("suzi_uncompressed.glb", "2CylinderEngine.glb")
TRAIN_MODELS = ("bunny_uncompressed.glb", "BoxTextured.glb", "AnimatedMorphCube.gltf")
# Built-in scenes worth learning from (the rest are covered by the procedural scenes).
BUILTINS = ("spheres", "cornell", "clearcoat", "sheen", "anisotropy", "iridescence",
            "specular", "ior", "glass", "liquid", "lights", "instances")


@dataclass
class View:
    """One render's setup; `scene` is a file path or a built-in name."""
    scene: str
    eye: tuple
    target: tuple
    fov: float
    env: str | None  # an HDRI's name, "builtin", or None
    env_rotation: float = 0.0
    env_intensity: float = 1.0
    kind: str = ""
    info: dict = field(default_factory=dict)


# ---------------------------------------------------------------------------------------
# A minimal glTF writer for procedural scenes (one buffer as a data URI).

class GltfBuilder:
    def __init__(self) -> None:
        self.doc = {"asset": {"version": "2.0", "generator": "pbrkit tools/denoiser"},
                    "scenes": [{"nodes": []}], "scene": 0, "nodes": [], "meshes": [],
                    "materials": [], "accessors": [], "bufferViews": [], "buffers": []}
        self.blob = bytearray()
        self.used: set[str] = set()
        self.lights: list = []

    def _view(self, data: bytes, target: int | None) -> int:
        while len(self.blob) % 4:
            self.blob.append(0)
        bv = {"buffer": 0, "byteOffset": len(self.blob), "byteLength": len(data)}
        if target:
            bv["target"] = target
        self.blob += data
        self.doc["bufferViews"].append(bv)
        return len(self.doc["bufferViews"]) - 1

    def _accessor(self, a: np.ndarray, type_: str, target: int) -> int:
        comp = 5125 if a.dtype == np.uint32 else 5126
        acc = {"bufferView": self._view(a.tobytes(), target), "componentType": comp,
               "count": int(a.shape[0]), "type": type_}
        if type_ == "VEC3" and comp == 5126:
            acc["min"] = a.min(axis=0).tolist()
            acc["max"] = a.max(axis=0).tolist()
        self.doc["accessors"].append(acc)
        return len(self.doc["accessors"]) - 1

    def material(self, m: dict) -> int:
        for ext in m.get("extensions", {}):
            self.used.add(ext)
        self.doc["materials"].append(m)
        return len(self.doc["materials"]) - 1

    def mesh(self, pos: np.ndarray, nrm: np.ndarray, uv: np.ndarray, idx: np.ndarray,
             material: int) -> int:
        prim = {"attributes": {
            "POSITION": self._accessor(pos.astype(np.float32), "VEC3", 34962),
            "NORMAL": self._accessor(nrm.astype(np.float32), "VEC3", 34962),
            "TEXCOORD_0": self._accessor(uv.astype(np.float32), "VEC2", 34962)},
            "indices": self._accessor(idx.astype(np.uint32).reshape(-1), "SCALAR", 34963),
            "material": material}
        self.doc["meshes"].append({"primitives": [prim]})
        return len(self.doc["meshes"]) - 1

    def node(self, mesh: int | None = None, translation=None, rotation=None, scale=None,
             light: int | None = None) -> None:
        n: dict = {}
        if mesh is not None:
            n["mesh"] = mesh
        if translation is not None:
            n["translation"] = [float(v) for v in translation]
        if rotation is not None:
            n["rotation"] = [float(v) for v in rotation]
        if scale is not None:
            n["scale"] = [float(v) for v in scale]
        if light is not None:
            n["extensions"] = {"KHR_lights_punctual": {"light": light}}
            self.used.add("KHR_lights_punctual")
        self.doc["nodes"].append(n)
        self.doc["scenes"][0]["nodes"].append(len(self.doc["nodes"]) - 1)

    def light(self, spec: dict) -> int:
        self.lights.append(spec)
        return len(self.lights) - 1

    def write(self, path: Path) -> None:
        self.doc["buffers"] = [{"byteLength": len(self.blob), "uri":
                                "data:application/octet-stream;base64," +
                                base64.b64encode(bytes(self.blob)).decode()}]
        if self.lights:
            self.doc["extensions"] = {"KHR_lights_punctual": {"lights": self.lights}}
        if self.used:
            self.doc["extensionsUsed"] = sorted(self.used)
        for key in ("materials", "meshes", "accessors", "bufferViews"):
            if not self.doc[key]:
                del self.doc[key]
        path.write_text(json.dumps(self.doc))


# ---------------------------------------------------------------------------------------
# Shapes (positions, normals, uvs, triangle indices).

def uv_sphere(r: float, n: int = 48):
    th = np.linspace(0, math.pi, n // 2 + 1)
    ph = np.linspace(0, 2 * math.pi, n + 1)
    t, p = np.meshgrid(th, ph, indexing="ij")
    nrm = np.stack([np.sin(t) * np.cos(p), np.cos(t), -np.sin(t) * np.sin(p)], -1).reshape(-1, 3)
    uv = np.stack([p / (2 * math.pi), t / math.pi], -1).reshape(-1, 2)
    rows, cols = t.shape
    i = np.arange(rows - 1)[:, None] * cols + np.arange(cols - 1)[None, :]
    tri = np.concatenate([np.stack([i, i + cols, i + 1], -1).reshape(-1, 3),
                          np.stack([i + 1, i + cols, i + cols + 1], -1).reshape(-1, 3)])
    return nrm * r, nrm, uv, tri


def box(size):
    sx, sy, sz = (s / 2 for s in size)
    pos, nrm, uv, tri = [], [], [], []
    for axis in range(3):
        for sign in (-1.0, 1.0):
            n = np.zeros(3)
            n[axis] = sign
            u = np.zeros(3)
            u[(axis + 1) % 3] = 1.0
            v = np.cross(n, u)
            c = n * np.array([sx, sy, sz])
            ext = np.array([sx, sy, sz])
            base = len(pos)
            for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                pos.append(c + a * u * ext + b * v * ext)
                nrm.append(n)
                uv.append(((a + 1) / 2, (b + 1) / 2))
            tri += [(base, base + 1, base + 2), (base, base + 2, base + 3)]
    return np.array(pos), np.array(nrm), np.array(uv), np.array(tri)


def quad(w: float, d: float, normal_up: bool = True):
    """A quad in the XZ plane facing +Y (or -Y)."""
    pos = np.array([[-w / 2, 0, -d / 2], [w / 2, 0, -d / 2], [w / 2, 0, d / 2], [-w / 2, 0, d / 2]])
    nrm = np.tile([0, 1 if normal_up else -1, 0], (4, 1)).astype(float)
    uv = np.array([[0, 0], [w, 0], [w, d], [0, d]]) / 2.0
    tri = np.array([[0, 2, 1], [0, 3, 2]]) if normal_up else np.array([[0, 1, 2], [0, 2, 3]])
    return pos, nrm, uv, tri


def torus(R: float, r: float, n: int = 48, m: int = 24):
    u = np.linspace(0, 2 * math.pi, n + 1)
    v = np.linspace(0, 2 * math.pi, m + 1)
    U, V = np.meshgrid(u, v, indexing="ij")
    cx, cz = np.cos(U), -np.sin(U)
    nrm = np.stack([np.cos(V) * cx, np.sin(V), np.cos(V) * cz], -1)
    pos = np.stack([R * cx, np.zeros_like(U), R * cz], -1) + r * nrm
    uv = np.stack([U / (2 * math.pi), V / (2 * math.pi)], -1)
    rows, cols = U.shape
    i = np.arange(rows - 1)[:, None] * cols + np.arange(cols - 1)[None, :]
    tri = np.concatenate([np.stack([i, i + 1, i + cols], -1).reshape(-1, 3),
                          np.stack([i + 1, i + cols + 1, i + cols], -1).reshape(-1, 3)])
    return pos.reshape(-1, 3), nrm.reshape(-1, 3), uv.reshape(-1, 2), tri


def quat_y(angle: float):
    return (0.0, math.sin(angle / 2), 0.0, math.cos(angle / 2))


# ---------------------------------------------------------------------------------------
# Materials over the whole schema.

def random_color(rng, lo=0.02, hi=0.95):
    return [float(v) for v in rng.uniform(lo, hi, 3)]


def random_roughness(rng):
    # Every roughness, with more weight near the smooth end where reflections show detail.
    return float(rng.choice([rng.uniform(0, 0.15), rng.uniform(0.15, 0.5), rng.uniform(0.5, 1)]))


def random_material(rng, textures: list[int]) -> dict:
    kind = rng.choice(["diffuse", "metal", "plastic", "glass", "sheen", "coat", "layered",
                       "emissive"], p=[0.18, 0.24, 0.16, 0.1, 0.08, 0.1, 0.1, 0.04])
    pbr: dict = {"baseColorFactor": random_color(rng) + [1.0],
                 "metallicFactor": 0.0, "roughnessFactor": random_roughness(rng)}
    ext: dict = {}
    m: dict = {"pbrMetallicRoughness": pbr, "doubleSided": True}
    if kind == "metal":
        pbr["metallicFactor"] = 1.0
        pbr["baseColorFactor"] = random_color(rng, 0.4, 1.0) + [1.0]
        if rng.random() < 0.25:
            ext["KHR_materials_anisotropy"] = {"anisotropyStrength": float(rng.uniform(0.3, 1)),
                                               "anisotropyRotation": float(rng.uniform(-3, 3))}
    elif kind == "plastic":
        ext["KHR_materials_specular"] = {"specularFactor": float(rng.uniform(0.5, 1)),
                                         "specularColorFactor": random_color(rng, 0.6, 1.0)}
        ext["KHR_materials_ior"] = {"ior": float(rng.uniform(1.3, 1.8))}
    elif kind == "glass":
        pbr["roughnessFactor"] = float(rng.choice([0.0, rng.uniform(0, 0.4)]))
        ext["KHR_materials_transmission"] = {"transmissionFactor": 1.0}
        ext["KHR_materials_ior"] = {"ior": float(rng.uniform(1.3, 1.8))}
        if rng.random() < 0.6:
            ext["KHR_materials_volume"] = {"thicknessFactor": float(rng.uniform(0.1, 1)),
                                           "attenuationColor": random_color(rng, 0.3, 1.0),
                                           "attenuationDistance": float(rng.uniform(0.2, 3))}
        if rng.random() < 0.15:
            ext["KHR_materials_dispersion"] = {"dispersion": float(rng.uniform(0.5, 3))}
    elif kind == "sheen":
        ext["KHR_materials_sheen"] = {"sheenColorFactor": random_color(rng, 0.3, 1.0),
                                      "sheenRoughnessFactor": float(rng.uniform(0.2, 1))}
    elif kind == "coat":
        pbr["metallicFactor"] = float(rng.choice([0.0, 1.0]))
        ext["KHR_materials_clearcoat"] = {"clearcoatFactor": float(rng.uniform(0.5, 1)),
                                          "clearcoatRoughnessFactor": float(rng.uniform(0, 0.3))}
    elif kind == "layered":
        if rng.random() < 0.5:
            ext["KHR_materials_iridescence"] = {"iridescenceFactor": 1.0,
                                                "iridescenceIor": float(rng.uniform(1.2, 2)),
                                                "iridescenceThicknessMaximum": float(rng.uniform(200, 900))}
            pbr["metallicFactor"] = float(rng.choice([0.0, 1.0]))
        else:
            ext["KHR_materials_diffuse_transmission"] = {
                "diffuseTransmissionFactor": float(rng.uniform(0.3, 1)),
                "diffuseTransmissionColorFactor": random_color(rng, 0.3, 1.0)}
    elif kind == "emissive":
        m["emissiveFactor"] = random_color(rng, 0.3, 1.0)
        ext["KHR_materials_emissive_strength"] = {"emissiveStrength": float(rng.uniform(1, 20))}
    if textures and rng.random() < 0.35:
        pbr["baseColorTexture"] = {"index": int(rng.choice(textures))}
    if ext:
        m["extensions"] = ext
    return m


def add_textures(builder: GltfBuilder, rng, tex_dir: Path) -> list[int]:
    """A few procedural textures (checkers, stripes, noise) written as PNG beside the scene."""
    import pbrkit
    textures = []
    builder.doc["images"] = []
    builder.doc["textures"] = []
    builder.doc["samplers"] = [{}]
    for k in range(3):
        n = 64
        y, x = np.mgrid[0:n, 0:n] / n
        freq = int(rng.integers(2, 12))
        c0, c1 = np.array(random_color(rng)), np.array(random_color(rng))
        pattern = rng.integers(0, 3)
        if pattern == 0:
            t = ((np.floor(x * freq) + np.floor(y * freq)) % 2)[..., None]
        elif pattern == 1:
            t = (np.sin(x * freq * 6.28) > 0)[..., None].astype(float)
        else:
            t = rng.random((n, n, 1))
        img = (c0 * (1 - t) + c1 * t).astype(np.float32)
        name = f"tex{k}.png"
        pbrkit.write_image(str(tex_dir / name), img)
        builder.doc["images"].append({"uri": name})
        builder.doc["textures"].append({"source": k, "sampler": 0})
        textures.append(k)
    return textures


def random_light(builder: GltfBuilder, rng, center, extent: float, *, room: bool) -> None:
    kind = rng.choice(["point", "spot", "directional"], p=[0.45, 0.35, 0.2] if not room else [0.6, 0.4, 0.0])
    color = [float(v) for v in rng.uniform(0.6, 1.0, 3)]
    if kind == "directional":
        idx = builder.light({"type": "directional", "color": color,
                             "intensity": float(rng.uniform(1, 6))})
        ang = rng.uniform(0, 2 * math.pi)
        tilt = rng.uniform(0.3, 1.2)
        # A rotation taking -Z down toward the scene from azimuth ang, elevation tilt.
        q = quat_from_to(np.array([0, 0, -1.0]), -np.array([math.cos(ang) * math.cos(tilt), math.sin(tilt), math.sin(ang) * math.cos(tilt)]))
        builder.node(light=idx, rotation=q)
        return
    pos = np.array(center) + rng.uniform(-1, 1, 3) * extent * np.array([1, 0.3, 1]) + np.array([0, extent * rng.uniform(0.6, 1.2), 0])
    intensity = float(rng.uniform(5, 60) * extent * extent)
    spec = {"type": str(kind), "color": color, "intensity": intensity}
    if kind == "spot":
        outer = float(rng.uniform(0.3, 0.9))
        spec["spot"] = {"innerConeAngle": outer * float(rng.uniform(0.2, 0.9)), "outerConeAngle": outer}
    idx = builder.light(spec)
    d = np.array(center) - pos
    builder.node(light=idx, translation=pos, rotation=quat_from_to(np.array([0, 0, -1.0]), d))


def quat_from_to(a: np.ndarray, b: np.ndarray):
    a = a / np.linalg.norm(a)
    b = b / np.linalg.norm(b)
    v = np.cross(a, b)
    w = 1.0 + float(np.dot(a, b))
    if w < 1e-6:
        return (1.0, 0.0, 0.0, 0.0)
    q = np.array([v[0], v[1], v[2], w])
    q /= np.linalg.norm(q)
    return tuple(float(x) for x in q)


def procedural_scene(rng, path: Path, *, interior: bool) -> tuple[dict, tuple, tuple, float, bool]:
    """Writes a random scene to `path`; returns (info, eye, target, fov, needs_env)."""
    b = GltfBuilder()
    textures = add_textures(b, rng, path.parent)
    floor_mat = b.material(random_material(rng, textures))
    floor = quad(30, 30)
    b.node(b.mesh(*floor, floor_mat))
    count = int(rng.integers(2, 9))
    shapes = []
    for _ in range(count):
        kind = rng.choice(["sphere", "box", "torus"], p=[0.5, 0.3, 0.2])
        mat = b.material(random_material(rng, textures))
        s = float(rng.uniform(0.3, 1.2))
        x, z = rng.uniform(-3, 3, 2)
        if kind == "sphere":
            mesh = b.mesh(*uv_sphere(s), mat)
            b.node(mesh, translation=(x, s, z))
        elif kind == "box":
            size = rng.uniform(0.4, 2.0, 3)
            mesh = b.mesh(*box(size), mat)
            b.node(mesh, translation=(x, size[1] / 2, z), rotation=quat_y(rng.uniform(0, 6.3)))
        else:
            mesh = b.mesh(*torus(s, s * rng.uniform(0.2, 0.45)), mat)
            b.node(mesh, translation=(x, s * 0.5, z), rotation=quat_from_to(np.array([0, 1.0, 0]), rng.normal(size=3)))
        shapes.append((x, z))
    needs_env = True
    if interior:
        # A room of six quads with a window (a gap in one wall) toward the environment,
        # or closed and lit by lights inside.
        wall = b.material({"pbrMetallicRoughness": {"baseColorFactor": random_color(rng, 0.3, 0.9) + [1.0],
                                                    "metallicFactor": 0.0, "roughnessFactor": 0.9},
                           "doubleSided": True})
        h = float(rng.uniform(3, 5))
        half = 5.0
        b.node(b.mesh(*quad(2 * half, 2 * half, normal_up=False), wall), translation=(0, h, 0))
        window = rng.random() < 0.6
        for k in range(4):
            ang = k * math.pi / 2
            rot = quat_from_to(np.array([0, 1.0, 0]), np.array([-math.sin(ang), 0, -math.cos(ang)]))
            cx, cz = math.sin(ang) * half, math.cos(ang) * half
            if window and k == 0:
                # the wall in two strips below and above a window opening
                for y0, y1 in ((0.0, h * 0.3), (h * 0.75, h)):
                    b.node(b.mesh(*quad(2 * half, y1 - y0), wall),
                           translation=(cx, (y0 + y1) / 2, cz), rotation=rot)
            else:
                b.node(b.mesh(*quad(2 * half, h), wall), translation=(cx, h / 2, cz), rotation=rot)
        for _ in range(int(rng.integers(0 if window else 1, 4))):
            random_light(b, rng, (0, 0, 0), 2.5, room=True)
        needs_env = window
        if window:
            random_light(b, rng, (0, 0, 0), 3.0, room=False) if rng.random() < 0.5 else None
    else:
        for _ in range(int(rng.integers(0, 3))):
            random_light(b, rng, (0, 0, 0), 3.0, room=False)
    b.write(path)
    target = np.array([*rng.uniform(-1.5, 1.5, 1), rng.uniform(0.2, 1.0), *rng.uniform(-1.5, 1.5, 1)])
    ang = rng.uniform(0, 2 * math.pi)
    dist = rng.uniform(3, 8) if not interior else rng.uniform(2, 4)
    eye = target + np.array([math.cos(ang) * dist, rng.uniform(0.3, 3.0), math.sin(ang) * dist])
    if interior:
        eye[1] = min(eye[1], 2.5)
    return ({"shapes": count, "interior": interior}, tuple(eye), tuple(target),
            float(rng.uniform(30, 70)), needs_env)


def orbit_camera(rng, lo, hi):
    lo, hi = np.array(lo), np.array(hi)
    c = (lo + hi) / 2
    r = float(np.linalg.norm(hi - lo)) / 2
    fov = float(rng.uniform(25, 60))
    dist = r / math.tan(math.radians(fov) / 2) * rng.uniform(0.5, 1.3)
    az = rng.uniform(0, 2 * math.pi)
    el = rng.uniform(-0.2, 1.1)
    d = np.array([math.cos(el) * math.cos(az), math.sin(el), math.cos(el) * math.sin(az)])
    target = c + rng.uniform(-0.3, 0.3, 3) * r
    return tuple(target + d * dist), tuple(target), fov
