# Type stub of the pbrkit package (pbrkit/__init__.py over the _pbrkit extension).
from os import PathLike
from typing import Any, Callable, Literal, Sequence, Tuple, Union, overload

import numpy as np
import numpy.typing as npt

FloatArray = npt.NDArray[np.float32]
ArrayLike = Union[FloatArray, Any]
StrPath = Union[str, "PathLike[str]"]
Progress = Callable[[float, str], Union[bool, None]]
Vec3 = Tuple[float, float, float]

class Error(RuntimeError): ...

class Camera:
    @property
    def name(self) -> str: ...
    @property
    def position(self) -> Vec3: ...
    @property
    def forward(self) -> Vec3: ...
    @property
    def yfov_degrees(self) -> float: ...
    @property
    def orthographic(self) -> bool: ...

class Scene:
    @property
    def source(self) -> str: ...
    @property
    def materials(self) -> list[dict[str, Any]]:
        """One dict per material: name, base_color, metallic, roughness, emissive (the
        factor times KHR_materials_emissive_strength), ior, double_sided, extensions (the
        KHR_materials_* surface extensions it uses) and extension_factors ({extension:
        {JSON property name: a number, or a tuple for a colour}})."""
        ...
    @property
    def cameras(self) -> list[Camera]: ...
    @property
    def lights(self) -> list[dict[str, Any]]: ...
    @property
    def bounds(self) -> Tuple[Vec3, Vec3]: ...
    @property
    def triangle_count(self) -> int: ...
    @property
    def mesh_count(self) -> int: ...
    @property
    def instance_count(self) -> int: ...
    @property
    def warnings(self) -> list[str]: ...
    @property
    def variants(self) -> list[str]:
        """The material variants' names (KHR_materials_variants), in the file's order;
        render(variant=) takes a name or an index."""
        ...
    @property
    def animations(self) -> list[dict[str, Any]]:
        """One dict per glTF animation, in the file's order: name, start and end (its
        first and last keyframe, seconds) and channels (how many properties it drives);
        render(animation=) and pose() take a name or an index."""
        ...
    def pose(self, animation: Union[str, int, None] = None, time: float = 0.0) -> None:
        """Poses the scene by `animation` at `time` seconds (clamped to its keys): its
        instance transforms, skinned and morphed meshes, cameras and lights, for every
        later render and for bounds, cameras and lights. pose() is the rest pose again."""
        ...

def builtin_scenes() -> list[str]: ...
def load(path_or_builtin_name: StrPath) -> Scene: ...
def look_at(eye: Sequence[float], target: Sequence[float],
            up: Sequence[float] = (0.0, 1.0, 0.0), fov: float = 45.0) -> Camera: ...

Env = Union[Literal["builtin"], StrPath, FloatArray, None]

@overload
def render(scene: Union[Scene, StrPath], renderer: Literal["path", "gl"] = "path", *,
           width: int | None = None, height: int | None = None, spp: int | None = None,
           seed: int | None = None, env: Env = "builtin", env_rotation: float = 0.0,
           env_intensity: float = 1.0, camera: Union[int, Camera, None] = None,
           model: Literal["reference", "classic"] = "reference",
           multiscatter: bool | None = None, max_bounces: int | None = None,
           time: float | None = None, noise_threshold: float | None = None,
           threads: int | None = None, denoise: bool | None = None,
           denoiser: Literal["learned", "classic"] | None = None, aovs: None = None,
           light_sampler: Literal["bvh", "power"] | None = None,
           variant: Union[str, int, None] = None,
           animation: Union[str, int, None] = None, animation_time: float = 0.0,
           progress: Progress | None = None) -> FloatArray: ...
@overload
def render(scene: Union[Scene, StrPath], renderer: Literal["path", "gl"] = "path", *,
           width: int | None = None, height: int | None = None, spp: int | None = None,
           seed: int | None = None, env: Env = "builtin", env_rotation: float = 0.0,
           env_intensity: float = 1.0, camera: Union[int, Camera, None] = None,
           model: Literal["reference", "classic"] = "reference",
           multiscatter: bool | None = None, max_bounces: int | None = None,
           time: float | None = None, noise_threshold: float | None = None,
           threads: int | None = None, denoise: bool | None = None,
           denoiser: Literal["learned", "classic"] | None = None,
           aovs: Union[str, Sequence[str]] = ...,
           light_sampler: Literal["bvh", "power"] | None = None,
           variant: Union[str, int, None] = None,
           animation: Union[str, int, None] = None, animation_time: float = 0.0,
           progress: Progress | None = None) -> Tuple[FloatArray, dict[str, FloatArray]]: ...

def denoise(color: Tuple[FloatArray, FloatArray], albedo: Tuple[FloatArray, FloatArray],
            normal: Tuple[FloatArray, FloatArray], depth: Tuple[FloatArray, FloatArray], *,
            denoiser: Literal["learned", "classic"] | None = None,
            progress: Progress | None = None) -> FloatArray: ...
def bake(env: Env = "builtin", *, rotation: float = 0.0, intensity: float = 1.0,
         face_size: int = 256, samples: int = 1024, irradiance_size: int = 32,
         lut_size: int = 128, model: Literal["reference", "classic"] = "reference",
         out_dir: StrPath | None = None, progress: Progress | None = None) -> dict[str, Any]: ...

def read_image(path: StrPath) -> FloatArray: ...
def read_exr_layers(path: str) -> dict[str, FloatArray]: ...
def write_image(path: str, image: FloatArray, half: bool = False, bits: int = 8,
                exposure: float = 0.0, tonemapper: str = "pbr-neutral") -> None: ...
def compare(a: FloatArray, b: FloatArray, mask: FloatArray | None = None) -> dict[str, float]: ...
def tonemap(image: FloatArray, exposure: float = 0.0,
            tonemapper: str = "pbr-neutral") -> FloatArray: ...
def tonemappers() -> list[str]: ...

def D(n_dot_h: ArrayLike, roughness: ArrayLike) -> FloatArray: ...
def G(n_dot_v: ArrayLike, n_dot_l: ArrayLike, roughness: ArrayLike,
      model: Literal["reference", "classic", "classic-ibl"] = "reference") -> FloatArray: ...
def F(cos_theta: ArrayLike, f0: ArrayLike) -> FloatArray: ...
def albedo(mu: ArrayLike, roughness: ArrayLike,
           model: Literal["reference", "classic", "classic-ibl"] = "reference") -> FloatArray: ...
