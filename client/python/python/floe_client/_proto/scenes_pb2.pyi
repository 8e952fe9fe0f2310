from google.protobuf.internal import containers as _containers
from google.protobuf.internal import enum_type_wrapper as _enum_type_wrapper
from google.protobuf import descriptor as _descriptor
from google.protobuf import message as _message
from collections.abc import Iterable as _Iterable, Mapping as _Mapping
from typing import ClassVar as _ClassVar, Optional as _Optional, Union as _Union

DESCRIPTOR: _descriptor.FileDescriptor

class SceneState(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    SCENE_STATE_UNSPECIFIED: _ClassVar[SceneState]
    SCENE_STATE_PAUSED: _ClassVar[SceneState]
    SCENE_STATE_RUNNING: _ClassVar[SceneState]
    SCENE_STATE_HALTED: _ClassVar[SceneState]
    SCENE_STATE_DELETED: _ClassVar[SceneState]

class Channel(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    CHANNEL_UNSPECIFIED: _ClassVar[Channel]
    CHANNEL_VELOCITY: _ClassVar[Channel]
    CHANNEL_DENSITY: _ClassVar[Channel]
    CHANNEL_PRESSURE: _ClassVar[Channel]

class FrameMode(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    FRAME_MODE_UNORDERED: _ClassVar[FrameMode]
    FRAME_MODE_IDENTITY: _ClassVar[FrameMode]
SCENE_STATE_UNSPECIFIED: SceneState
SCENE_STATE_PAUSED: SceneState
SCENE_STATE_RUNNING: SceneState
SCENE_STATE_HALTED: SceneState
SCENE_STATE_DELETED: SceneState
CHANNEL_UNSPECIFIED: Channel
CHANNEL_VELOCITY: Channel
CHANNEL_DENSITY: Channel
CHANNEL_PRESSURE: Channel
FRAME_MODE_UNORDERED: FrameMode
FRAME_MODE_IDENTITY: FrameMode

class SceneRef(_message.Message):
    __slots__ = ("scene_id",)
    SCENE_ID_FIELD_NUMBER: _ClassVar[int]
    scene_id: int
    def __init__(self, scene_id: _Optional[int] = ...) -> None: ...

class CreateSceneRequest(_message.Message):
    __slots__ = ("preset", "document", "document_format", "overrides", "backend")
    PRESET_FIELD_NUMBER: _ClassVar[int]
    DOCUMENT_FIELD_NUMBER: _ClassVar[int]
    DOCUMENT_FORMAT_FIELD_NUMBER: _ClassVar[int]
    OVERRIDES_FIELD_NUMBER: _ClassVar[int]
    BACKEND_FIELD_NUMBER: _ClassVar[int]
    preset: str
    document: str
    document_format: str
    overrides: _containers.RepeatedScalarFieldContainer[str]
    backend: str
    def __init__(self, preset: _Optional[str] = ..., document: _Optional[str] = ..., document_format: _Optional[str] = ..., overrides: _Optional[_Iterable[str]] = ..., backend: _Optional[str] = ...) -> None: ...

class SceneInfo(_message.Message):
    __slots__ = ("scene_id", "name", "state", "sim_time", "steps", "particles", "bounds_min", "bounds_max", "halt_reason", "scene_json", "backend", "channels", "sets", "tunables", "materials", "owner", "worker", "sizing")
    SCENE_ID_FIELD_NUMBER: _ClassVar[int]
    NAME_FIELD_NUMBER: _ClassVar[int]
    STATE_FIELD_NUMBER: _ClassVar[int]
    SIM_TIME_FIELD_NUMBER: _ClassVar[int]
    STEPS_FIELD_NUMBER: _ClassVar[int]
    PARTICLES_FIELD_NUMBER: _ClassVar[int]
    BOUNDS_MIN_FIELD_NUMBER: _ClassVar[int]
    BOUNDS_MAX_FIELD_NUMBER: _ClassVar[int]
    HALT_REASON_FIELD_NUMBER: _ClassVar[int]
    SCENE_JSON_FIELD_NUMBER: _ClassVar[int]
    BACKEND_FIELD_NUMBER: _ClassVar[int]
    CHANNELS_FIELD_NUMBER: _ClassVar[int]
    SETS_FIELD_NUMBER: _ClassVar[int]
    TUNABLES_FIELD_NUMBER: _ClassVar[int]
    MATERIALS_FIELD_NUMBER: _ClassVar[int]
    OWNER_FIELD_NUMBER: _ClassVar[int]
    WORKER_FIELD_NUMBER: _ClassVar[int]
    SIZING_FIELD_NUMBER: _ClassVar[int]
    scene_id: int
    name: str
    state: SceneState
    sim_time: float
    steps: int
    particles: int
    bounds_min: _containers.RepeatedScalarFieldContainer[float]
    bounds_max: _containers.RepeatedScalarFieldContainer[float]
    halt_reason: str
    scene_json: str
    backend: str
    channels: _containers.RepeatedCompositeFieldContainer[ChannelDescription]
    sets: _containers.RepeatedCompositeFieldContainer[ParticleSet]
    tunables: _containers.RepeatedCompositeFieldContainer[Tunable]
    materials: _containers.RepeatedCompositeFieldContainer[MaterialDescription]
    owner: str
    worker: str
    sizing: Sizing
    def __init__(self, scene_id: _Optional[int] = ..., name: _Optional[str] = ..., state: _Optional[_Union[SceneState, str]] = ..., sim_time: _Optional[float] = ..., steps: _Optional[int] = ..., particles: _Optional[int] = ..., bounds_min: _Optional[_Iterable[float]] = ..., bounds_max: _Optional[_Iterable[float]] = ..., halt_reason: _Optional[str] = ..., scene_json: _Optional[str] = ..., backend: _Optional[str] = ..., channels: _Optional[_Iterable[_Union[ChannelDescription, _Mapping]]] = ..., sets: _Optional[_Iterable[_Union[ParticleSet, _Mapping]]] = ..., tunables: _Optional[_Iterable[_Union[Tunable, _Mapping]]] = ..., materials: _Optional[_Iterable[_Union[MaterialDescription, _Mapping]]] = ..., owner: _Optional[str] = ..., worker: _Optional[str] = ..., sizing: _Optional[_Union[Sizing, _Mapping]] = ...) -> None: ...

class Sizing(_message.Message):
    __slots__ = ("spacing", "particles", "real_time_factor", "full_spacing", "full_particles")
    SPACING_FIELD_NUMBER: _ClassVar[int]
    PARTICLES_FIELD_NUMBER: _ClassVar[int]
    REAL_TIME_FACTOR_FIELD_NUMBER: _ClassVar[int]
    FULL_SPACING_FIELD_NUMBER: _ClassVar[int]
    FULL_PARTICLES_FIELD_NUMBER: _ClassVar[int]
    spacing: float
    particles: int
    real_time_factor: float
    full_spacing: float
    full_particles: int
    def __init__(self, spacing: _Optional[float] = ..., particles: _Optional[int] = ..., real_time_factor: _Optional[float] = ..., full_spacing: _Optional[float] = ..., full_particles: _Optional[int] = ...) -> None: ...

class ChannelDescription(_message.Message):
    __slots__ = ("name", "tag", "unit", "components", "set", "exact", "about", "module")
    NAME_FIELD_NUMBER: _ClassVar[int]
    TAG_FIELD_NUMBER: _ClassVar[int]
    UNIT_FIELD_NUMBER: _ClassVar[int]
    COMPONENTS_FIELD_NUMBER: _ClassVar[int]
    SET_FIELD_NUMBER: _ClassVar[int]
    EXACT_FIELD_NUMBER: _ClassVar[int]
    ABOUT_FIELD_NUMBER: _ClassVar[int]
    MODULE_FIELD_NUMBER: _ClassVar[int]
    name: str
    tag: int
    unit: str
    components: int
    set: str
    exact: bool
    about: str
    module: str
    def __init__(self, name: _Optional[str] = ..., tag: _Optional[int] = ..., unit: _Optional[str] = ..., components: _Optional[int] = ..., set: _Optional[str] = ..., exact: _Optional[bool] = ..., about: _Optional[str] = ..., module: _Optional[str] = ...) -> None: ...

class ParticleSet(_message.Message):
    __slots__ = ("name", "count", "index", "grid", "look", "surface", "shade", "part_of")
    NAME_FIELD_NUMBER: _ClassVar[int]
    COUNT_FIELD_NUMBER: _ClassVar[int]
    INDEX_FIELD_NUMBER: _ClassVar[int]
    GRID_FIELD_NUMBER: _ClassVar[int]
    LOOK_FIELD_NUMBER: _ClassVar[int]
    SURFACE_FIELD_NUMBER: _ClassVar[int]
    SHADE_FIELD_NUMBER: _ClassVar[int]
    PART_OF_FIELD_NUMBER: _ClassVar[int]
    name: str
    count: int
    index: int
    grid: bool
    look: str
    surface: str
    shade: str
    part_of: str
    def __init__(self, name: _Optional[str] = ..., count: _Optional[int] = ..., index: _Optional[int] = ..., grid: _Optional[bool] = ..., look: _Optional[str] = ..., surface: _Optional[str] = ..., shade: _Optional[str] = ..., part_of: _Optional[str] = ...) -> None: ...

class MaterialDescription(_message.Message):
    __slots__ = ("name", "kind", "rest_density", "look")
    NAME_FIELD_NUMBER: _ClassVar[int]
    KIND_FIELD_NUMBER: _ClassVar[int]
    REST_DENSITY_FIELD_NUMBER: _ClassVar[int]
    LOOK_FIELD_NUMBER: _ClassVar[int]
    name: str
    kind: str
    rest_density: float
    look: str
    def __init__(self, name: _Optional[str] = ..., kind: _Optional[str] = ..., rest_density: _Optional[float] = ..., look: _Optional[str] = ...) -> None: ...

class Tunable(_message.Message):
    __slots__ = ("path", "unit", "min", "max", "about", "module")
    PATH_FIELD_NUMBER: _ClassVar[int]
    UNIT_FIELD_NUMBER: _ClassVar[int]
    MIN_FIELD_NUMBER: _ClassVar[int]
    MAX_FIELD_NUMBER: _ClassVar[int]
    ABOUT_FIELD_NUMBER: _ClassVar[int]
    MODULE_FIELD_NUMBER: _ClassVar[int]
    path: str
    unit: str
    min: float
    max: float
    about: str
    module: str
    def __init__(self, path: _Optional[str] = ..., unit: _Optional[str] = ..., min: _Optional[float] = ..., max: _Optional[float] = ..., about: _Optional[str] = ..., module: _Optional[str] = ...) -> None: ...

class ListScenesRequest(_message.Message):
    __slots__ = ()
    def __init__(self) -> None: ...

class ListScenesResponse(_message.Message):
    __slots__ = ("scenes",)
    SCENES_FIELD_NUMBER: _ClassVar[int]
    scenes: _containers.RepeatedCompositeFieldContainer[SceneInfo]
    def __init__(self, scenes: _Optional[_Iterable[_Union[SceneInfo, _Mapping]]] = ...) -> None: ...

class ListPresetsRequest(_message.Message):
    __slots__ = ()
    def __init__(self) -> None: ...

class ListPresetsResponse(_message.Message):
    __slots__ = ("presets",)
    PRESETS_FIELD_NUMBER: _ClassVar[int]
    presets: _containers.RepeatedCompositeFieldContainer[PresetInfo]
    def __init__(self, presets: _Optional[_Iterable[_Union[PresetInfo, _Mapping]]] = ...) -> None: ...

class PresetInfo(_message.Message):
    __slots__ = ("name", "about")
    NAME_FIELD_NUMBER: _ClassVar[int]
    ABOUT_FIELD_NUMBER: _ClassVar[int]
    name: str
    about: str
    def __init__(self, name: _Optional[str] = ..., about: _Optional[str] = ...) -> None: ...

class SetParametersRequest(_message.Message):
    __slots__ = ("scene_id", "overrides")
    SCENE_ID_FIELD_NUMBER: _ClassVar[int]
    OVERRIDES_FIELD_NUMBER: _ClassVar[int]
    scene_id: int
    overrides: _containers.RepeatedScalarFieldContainer[str]
    def __init__(self, scene_id: _Optional[int] = ..., overrides: _Optional[_Iterable[str]] = ...) -> None: ...

class SceneSnapshot(_message.Message):
    __slots__ = ("scene_id", "state")
    SCENE_ID_FIELD_NUMBER: _ClassVar[int]
    STATE_FIELD_NUMBER: _ClassVar[int]
    scene_id: int
    state: bytes
    def __init__(self, scene_id: _Optional[int] = ..., state: _Optional[bytes] = ...) -> None: ...

class RestoreRequest(_message.Message):
    __slots__ = ("scene_id", "state")
    SCENE_ID_FIELD_NUMBER: _ClassVar[int]
    STATE_FIELD_NUMBER: _ClassVar[int]
    scene_id: int
    state: bytes
    def __init__(self, scene_id: _Optional[int] = ..., state: _Optional[bytes] = ...) -> None: ...

class StepRequest(_message.Message):
    __slots__ = ("scene_id", "steps", "until_time")
    SCENE_ID_FIELD_NUMBER: _ClassVar[int]
    STEPS_FIELD_NUMBER: _ClassVar[int]
    UNTIL_TIME_FIELD_NUMBER: _ClassVar[int]
    scene_id: int
    steps: int
    until_time: float
    def __init__(self, scene_id: _Optional[int] = ..., steps: _Optional[int] = ..., until_time: _Optional[float] = ...) -> None: ...

class RunRequest(_message.Message):
    __slots__ = ("scene_id", "real_time_factor")
    SCENE_ID_FIELD_NUMBER: _ClassVar[int]
    REAL_TIME_FACTOR_FIELD_NUMBER: _ClassVar[int]
    scene_id: int
    real_time_factor: float
    def __init__(self, scene_id: _Optional[int] = ..., real_time_factor: _Optional[float] = ...) -> None: ...

class SceneStats(_message.Message):
    __slots__ = ("scene_id", "state", "sim_time", "steps", "particles", "steps_per_second", "dt", "subscribers", "dropped_frames", "frames_published", "sets", "measures", "name", "owner", "frame_bytes", "worker")
    SCENE_ID_FIELD_NUMBER: _ClassVar[int]
    STATE_FIELD_NUMBER: _ClassVar[int]
    SIM_TIME_FIELD_NUMBER: _ClassVar[int]
    STEPS_FIELD_NUMBER: _ClassVar[int]
    PARTICLES_FIELD_NUMBER: _ClassVar[int]
    STEPS_PER_SECOND_FIELD_NUMBER: _ClassVar[int]
    DT_FIELD_NUMBER: _ClassVar[int]
    SUBSCRIBERS_FIELD_NUMBER: _ClassVar[int]
    DROPPED_FRAMES_FIELD_NUMBER: _ClassVar[int]
    FRAMES_PUBLISHED_FIELD_NUMBER: _ClassVar[int]
    SETS_FIELD_NUMBER: _ClassVar[int]
    MEASURES_FIELD_NUMBER: _ClassVar[int]
    NAME_FIELD_NUMBER: _ClassVar[int]
    OWNER_FIELD_NUMBER: _ClassVar[int]
    FRAME_BYTES_FIELD_NUMBER: _ClassVar[int]
    WORKER_FIELD_NUMBER: _ClassVar[int]
    scene_id: int
    state: SceneState
    sim_time: float
    steps: int
    particles: int
    steps_per_second: float
    dt: float
    subscribers: int
    dropped_frames: int
    frames_published: int
    sets: _containers.RepeatedCompositeFieldContainer[ParticleSet]
    measures: _containers.RepeatedCompositeFieldContainer[Measure]
    name: str
    owner: str
    frame_bytes: int
    worker: str
    def __init__(self, scene_id: _Optional[int] = ..., state: _Optional[_Union[SceneState, str]] = ..., sim_time: _Optional[float] = ..., steps: _Optional[int] = ..., particles: _Optional[int] = ..., steps_per_second: _Optional[float] = ..., dt: _Optional[float] = ..., subscribers: _Optional[int] = ..., dropped_frames: _Optional[int] = ..., frames_published: _Optional[int] = ..., sets: _Optional[_Iterable[_Union[ParticleSet, _Mapping]]] = ..., measures: _Optional[_Iterable[_Union[Measure, _Mapping]]] = ..., name: _Optional[str] = ..., owner: _Optional[str] = ..., frame_bytes: _Optional[int] = ..., worker: _Optional[str] = ...) -> None: ...

class Measure(_message.Message):
    __slots__ = ("name", "value", "unit")
    NAME_FIELD_NUMBER: _ClassVar[int]
    VALUE_FIELD_NUMBER: _ClassVar[int]
    UNIT_FIELD_NUMBER: _ClassVar[int]
    name: str
    value: float
    unit: str
    def __init__(self, name: _Optional[str] = ..., value: _Optional[float] = ..., unit: _Optional[str] = ...) -> None: ...

class StreamFramesRequest(_message.Message):
    __slots__ = ("scene_id", "channels", "max_fps", "position_bits", "mode", "decimation", "channel_names", "particle_set", "view")
    SCENE_ID_FIELD_NUMBER: _ClassVar[int]
    CHANNELS_FIELD_NUMBER: _ClassVar[int]
    MAX_FPS_FIELD_NUMBER: _ClassVar[int]
    POSITION_BITS_FIELD_NUMBER: _ClassVar[int]
    MODE_FIELD_NUMBER: _ClassVar[int]
    DECIMATION_FIELD_NUMBER: _ClassVar[int]
    CHANNEL_NAMES_FIELD_NUMBER: _ClassVar[int]
    PARTICLE_SET_FIELD_NUMBER: _ClassVar[int]
    VIEW_FIELD_NUMBER: _ClassVar[int]
    scene_id: int
    channels: _containers.RepeatedScalarFieldContainer[Channel]
    max_fps: float
    position_bits: int
    mode: FrameMode
    decimation: int
    channel_names: _containers.RepeatedScalarFieldContainer[str]
    particle_set: str
    view: FrameView
    def __init__(self, scene_id: _Optional[int] = ..., channels: _Optional[_Iterable[_Union[Channel, str]]] = ..., max_fps: _Optional[float] = ..., position_bits: _Optional[int] = ..., mode: _Optional[_Union[FrameMode, str]] = ..., decimation: _Optional[int] = ..., channel_names: _Optional[_Iterable[str]] = ..., particle_set: _Optional[str] = ..., view: _Optional[_Union[FrameView, _Mapping]] = ...) -> None: ...

class FrameView(_message.Message):
    __slots__ = ("box", "camera", "budget")
    BOX_FIELD_NUMBER: _ClassVar[int]
    CAMERA_FIELD_NUMBER: _ClassVar[int]
    BUDGET_FIELD_NUMBER: _ClassVar[int]
    box: ViewBox
    camera: ViewCamera
    budget: int
    def __init__(self, box: _Optional[_Union[ViewBox, _Mapping]] = ..., camera: _Optional[_Union[ViewCamera, _Mapping]] = ..., budget: _Optional[int] = ...) -> None: ...

class ViewBox(_message.Message):
    __slots__ = ("min", "max")
    MIN_FIELD_NUMBER: _ClassVar[int]
    MAX_FIELD_NUMBER: _ClassVar[int]
    min: _containers.RepeatedScalarFieldContainer[float]
    max: _containers.RepeatedScalarFieldContainer[float]
    def __init__(self, min: _Optional[_Iterable[float]] = ..., max: _Optional[_Iterable[float]] = ...) -> None: ...

class ViewCamera(_message.Message):
    __slots__ = ("position", "direction", "fov_deg", "far")
    POSITION_FIELD_NUMBER: _ClassVar[int]
    DIRECTION_FIELD_NUMBER: _ClassVar[int]
    FOV_DEG_FIELD_NUMBER: _ClassVar[int]
    FAR_FIELD_NUMBER: _ClassVar[int]
    position: _containers.RepeatedScalarFieldContainer[float]
    direction: _containers.RepeatedScalarFieldContainer[float]
    fov_deg: float
    far: float
    def __init__(self, position: _Optional[_Iterable[float]] = ..., direction: _Optional[_Iterable[float]] = ..., fov_deg: _Optional[float] = ..., far: _Optional[float] = ...) -> None: ...

class WatchFramesRequest(_message.Message):
    __slots__ = ("start", "view")
    START_FIELD_NUMBER: _ClassVar[int]
    VIEW_FIELD_NUMBER: _ClassVar[int]
    start: StreamFramesRequest
    view: FrameView
    def __init__(self, start: _Optional[_Union[StreamFramesRequest, _Mapping]] = ..., view: _Optional[_Union[FrameView, _Mapping]] = ...) -> None: ...

class Frame(_message.Message):
    __slots__ = ("data", "sequence", "skipped")
    DATA_FIELD_NUMBER: _ClassVar[int]
    SEQUENCE_FIELD_NUMBER: _ClassVar[int]
    SKIPPED_FIELD_NUMBER: _ClassVar[int]
    data: bytes
    sequence: int
    skipped: int
    def __init__(self, data: _Optional[bytes] = ..., sequence: _Optional[int] = ..., skipped: _Optional[int] = ...) -> None: ...

class SceneEvent(_message.Message):
    __slots__ = ("scene_id", "halted", "deleted", "parameter_changed", "step_abandoned")
    SCENE_ID_FIELD_NUMBER: _ClassVar[int]
    HALTED_FIELD_NUMBER: _ClassVar[int]
    DELETED_FIELD_NUMBER: _ClassVar[int]
    PARAMETER_CHANGED_FIELD_NUMBER: _ClassVar[int]
    STEP_ABANDONED_FIELD_NUMBER: _ClassVar[int]
    scene_id: int
    halted: Halted
    deleted: Deleted
    parameter_changed: ParameterChanged
    step_abandoned: StepAbandoned
    def __init__(self, scene_id: _Optional[int] = ..., halted: _Optional[_Union[Halted, _Mapping]] = ..., deleted: _Optional[_Union[Deleted, _Mapping]] = ..., parameter_changed: _Optional[_Union[ParameterChanged, _Mapping]] = ..., step_abandoned: _Optional[_Union[StepAbandoned, _Mapping]] = ...) -> None: ...

class StepAbandoned(_message.Message):
    __slots__ = ("left_at_step", "stopped_at_step")
    LEFT_AT_STEP_FIELD_NUMBER: _ClassVar[int]
    STOPPED_AT_STEP_FIELD_NUMBER: _ClassVar[int]
    left_at_step: int
    stopped_at_step: int
    def __init__(self, left_at_step: _Optional[int] = ..., stopped_at_step: _Optional[int] = ...) -> None: ...

class ParameterChanged(_message.Message):
    __slots__ = ("overrides",)
    OVERRIDES_FIELD_NUMBER: _ClassVar[int]
    overrides: _containers.RepeatedScalarFieldContainer[str]
    def __init__(self, overrides: _Optional[_Iterable[str]] = ...) -> None: ...

class Halted(_message.Message):
    __slots__ = ("step", "sim_time", "reason", "particle")
    STEP_FIELD_NUMBER: _ClassVar[int]
    SIM_TIME_FIELD_NUMBER: _ClassVar[int]
    REASON_FIELD_NUMBER: _ClassVar[int]
    PARTICLE_FIELD_NUMBER: _ClassVar[int]
    step: int
    sim_time: float
    reason: str
    particle: int
    def __init__(self, step: _Optional[int] = ..., sim_time: _Optional[float] = ..., reason: _Optional[str] = ..., particle: _Optional[int] = ...) -> None: ...

class Deleted(_message.Message):
    __slots__ = ()
    def __init__(self) -> None: ...

class CheckpointInfo(_message.Message):
    __slots__ = ("scene_id", "sequence", "step", "sim_time")
    SCENE_ID_FIELD_NUMBER: _ClassVar[int]
    SEQUENCE_FIELD_NUMBER: _ClassVar[int]
    STEP_FIELD_NUMBER: _ClassVar[int]
    SIM_TIME_FIELD_NUMBER: _ClassVar[int]
    scene_id: int
    sequence: int
    step: int
    sim_time: float
    def __init__(self, scene_id: _Optional[int] = ..., sequence: _Optional[int] = ..., step: _Optional[int] = ..., sim_time: _Optional[float] = ...) -> None: ...

class ShareLink(_message.Message):
    __slots__ = ("scene_id", "share_id", "token")
    SCENE_ID_FIELD_NUMBER: _ClassVar[int]
    SHARE_ID_FIELD_NUMBER: _ClassVar[int]
    TOKEN_FIELD_NUMBER: _ClassVar[int]
    scene_id: int
    share_id: str
    token: str
    def __init__(self, scene_id: _Optional[int] = ..., share_id: _Optional[str] = ..., token: _Optional[str] = ...) -> None: ...

class ShareList(_message.Message):
    __slots__ = ("scene_id", "share_ids")
    SCENE_ID_FIELD_NUMBER: _ClassVar[int]
    SHARE_IDS_FIELD_NUMBER: _ClassVar[int]
    scene_id: int
    share_ids: _containers.RepeatedScalarFieldContainer[str]
    def __init__(self, scene_id: _Optional[int] = ..., share_ids: _Optional[_Iterable[str]] = ...) -> None: ...

class RevokeShareRequest(_message.Message):
    __slots__ = ("scene_id", "share_id")
    SCENE_ID_FIELD_NUMBER: _ClassVar[int]
    SHARE_ID_FIELD_NUMBER: _ClassVar[int]
    scene_id: int
    share_id: str
    def __init__(self, scene_id: _Optional[int] = ..., share_id: _Optional[str] = ...) -> None: ...

class SceneStatsList(_message.Message):
    __slots__ = ("scenes",)
    SCENES_FIELD_NUMBER: _ClassVar[int]
    scenes: _containers.RepeatedCompositeFieldContainer[SceneStats]
    def __init__(self, scenes: _Optional[_Iterable[_Union[SceneStats, _Mapping]]] = ...) -> None: ...

class WhoAmIRequest(_message.Message):
    __slots__ = ()
    def __init__(self) -> None: ...

class QuotaValue(_message.Message):
    __slots__ = ("name", "value", "overridden")
    NAME_FIELD_NUMBER: _ClassVar[int]
    VALUE_FIELD_NUMBER: _ClassVar[int]
    OVERRIDDEN_FIELD_NUMBER: _ClassVar[int]
    name: str
    value: int
    overridden: bool
    def __init__(self, name: _Optional[str] = ..., value: _Optional[int] = ..., overridden: _Optional[bool] = ...) -> None: ...

class UserInfo(_message.Message):
    __slots__ = ("name", "admin", "quotas", "scenes", "running_scenes", "running_particles", "open_streams")
    NAME_FIELD_NUMBER: _ClassVar[int]
    ADMIN_FIELD_NUMBER: _ClassVar[int]
    QUOTAS_FIELD_NUMBER: _ClassVar[int]
    SCENES_FIELD_NUMBER: _ClassVar[int]
    RUNNING_SCENES_FIELD_NUMBER: _ClassVar[int]
    RUNNING_PARTICLES_FIELD_NUMBER: _ClassVar[int]
    OPEN_STREAMS_FIELD_NUMBER: _ClassVar[int]
    name: str
    admin: bool
    quotas: _containers.RepeatedCompositeFieldContainer[QuotaValue]
    scenes: int
    running_scenes: int
    running_particles: int
    open_streams: int
    def __init__(self, name: _Optional[str] = ..., admin: _Optional[bool] = ..., quotas: _Optional[_Iterable[_Union[QuotaValue, _Mapping]]] = ..., scenes: _Optional[int] = ..., running_scenes: _Optional[int] = ..., running_particles: _Optional[int] = ..., open_streams: _Optional[int] = ...) -> None: ...

class ListUsersRequest(_message.Message):
    __slots__ = ()
    def __init__(self) -> None: ...

class ListUsersResponse(_message.Message):
    __slots__ = ("users",)
    USERS_FIELD_NUMBER: _ClassVar[int]
    users: _containers.RepeatedCompositeFieldContainer[UserInfo]
    def __init__(self, users: _Optional[_Iterable[_Union[UserInfo, _Mapping]]] = ...) -> None: ...

class SetQuotaRequest(_message.Message):
    __slots__ = ("user", "quota", "value")
    USER_FIELD_NUMBER: _ClassVar[int]
    QUOTA_FIELD_NUMBER: _ClassVar[int]
    VALUE_FIELD_NUMBER: _ClassVar[int]
    user: str
    quota: str
    value: int
    def __init__(self, user: _Optional[str] = ..., quota: _Optional[str] = ..., value: _Optional[int] = ...) -> None: ...
