"""Spoken dialogue: speech to text (`stt`), text to speech (`tts`, `speakers`) and the `hexar listen` loop (`loop`).

Nothing is imported here: the speech packages are optional and slow to load.
"""
