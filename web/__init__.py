"""See why: the path/timeline figure, the annotated MCAP recording and the `hexar web` page."""
