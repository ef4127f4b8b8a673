"""Errors of spoken dialogue; each is reported as one line and exit code 2."""

from __future__ import annotations

from hexar.errors import HexarError


class VoiceError(HexarError):
    """Something about speech in or out went wrong."""


class AudioFormatError(VoiceError):
    """An audio file that is not a WAV, or a WAV encoding this reader does not support."""


class NoSpeechError(VoiceError):
    """The audio held no speech."""


class MicrophoneError(VoiceError):
    """No microphone to listen with."""


class TranscriberError(VoiceError):
    """A speech recogniser that cannot be loaded or run (missing package or model)."""


class SpeakerError(VoiceError):
    """No way to speak or write the answer (missing synthesiser, robot TTS failed)."""
