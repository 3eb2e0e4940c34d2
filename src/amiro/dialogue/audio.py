"""Audio as 16-bit mono samples: WAV in and out, resampling to the recognisers' 16 kHz and the
per-speaker preprocessing of the profiles (gain, high-pass)."""

from __future__ import annotations

import io
import warnings
import wave
from dataclasses import dataclass
from math import gcd
from pathlib import Path

import numpy as np
import numpy.typing as npt
from scipy import signal
from scipy.io import wavfile

from amiro.core.config import ConfigError

ASR_RATE = 16000


@dataclass(frozen=True)
class Audio:
    samples: npt.NDArray[np.int16]
    rate: int

    @property
    def seconds(self) -> float:
        return len(self.samples) / self.rate

    def to_bytes(self) -> bytes:
        return self.samples.astype("<i2").tobytes()


def read_wav_bytes(data: bytes, source: str = "audio") -> Audio:
    """Any PCM (8, 16, 24, 32 bit) or float WAV, any rate, mono or several channels: 16-bit
    mono at the file's rate (channels averaged); :func:`resample` takes it to 16 kHz."""
    try:
        with warnings.catch_warnings():  # a streamed WAV (espeak-ng --stdout) has no length
            warnings.simplefilter("ignore", wavfile.WavFileWarning)
            rate, x = wavfile.read(io.BytesIO(data))
    except (ValueError, EOFError, OSError) as exc:
        raise ConfigError(f"{source}: not a WAV file ({exc})") from None
    if x.dtype.kind == "f":
        scaled = x.astype(np.float64) * 32768.0
    elif x.dtype == np.uint8:  # 8-bit WAV is unsigned
        scaled = (x.astype(np.float64) - 128.0) * 256.0
    else:
        scaled = x.astype(np.float64) / 2.0 ** (8 * x.dtype.itemsize - 16)
    mono = scaled.mean(axis=1) if scaled.ndim == 2 else scaled
    return Audio(np.clip(np.round(mono), -32768, 32767).astype(np.int16), int(rate))


def read_wav(path: Path) -> Audio:
    if not path.is_file():
        raise ConfigError(f"{path}: no such file")
    return read_wav_bytes(path.read_bytes(), str(path))


def write_wav(path: Path, audio: Audio) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    with wave.open(str(path), "wb") as w:
        w.setnchannels(1)
        w.setsampwidth(2)
        w.setframerate(audio.rate)
        w.writeframes(audio.to_bytes())


def resample(audio: Audio, rate: int = ASR_RATE) -> Audio:
    if audio.rate == rate:
        return audio
    g = gcd(audio.rate, rate)
    out = signal.resample_poly(audio.samples.astype(np.float64), rate // g, audio.rate // g)
    return Audio(np.clip(out, -32768, 32767).astype(np.int16), rate)


def preprocess(audio: Audio, gain_db: float = 0.0, highpass_hz: float = 0.0) -> Audio:
    """A speaker's audio settings: remove rumble below ``highpass_hz``, then apply gain."""
    x = audio.samples.astype(np.float64)
    if highpass_hz > 0.0:
        sos = signal.butter(2, highpass_hz, "highpass", fs=audio.rate, output="sos")
        x = signal.sosfilt(sos, x)
    x *= 10.0 ** (gain_db / 20.0)
    return Audio(np.clip(x, -32768, 32767).astype(np.int16), audio.rate)


def add_white_noise(audio: Audio, rng: np.random.Generator, rms: float) -> Audio:
    x = audio.samples.astype(np.float64) + rng.normal(0.0, rms, len(audio.samples))
    return Audio(np.clip(np.round(x), -32768, 32767).astype(np.int16), audio.rate)


def add_noise_at_snr(audio: Audio, rng: np.random.Generator, snr_db: float) -> Audio:
    """White noise ``snr_db`` below the recording's mean power (silences included)."""
    power = float(np.mean(audio.samples.astype(np.float64) ** 2))
    return add_white_noise(audio, rng, (power / 10.0 ** (snr_db / 10.0)) ** 0.5)


def add_noise_floor(audio: Audio, rng: np.random.Generator, rms: float = 10.0) -> Audio:
    """Audio with a faint noise floor (``rms`` in sample units, about -70 dBFS by default), as
    any microphone has.  Synthetic speech has stretches of exact digital silence whose log
    energy the recogniser's features cannot represent: measured on espeak-ng commands,
    pocketsphinx's grammar search then fails to reach the end of the sentence."""
    return add_white_noise(audio, rng, rms)
