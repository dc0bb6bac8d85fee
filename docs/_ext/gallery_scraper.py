"""Figures of the gallery saved with their outside legends (``bbox_inches="tight"``)."""

from sphinx_gallery.scrapers import matplotlib_scraper


class TightScraper:
    """sphinx-gallery's matplotlib scraper, figures cropped to what they draw."""

    def __repr__(self):                 # a stable name: the configuration stays cacheable
        return self.__class__.__name__

    def __call__(self, *args, **kwargs):
        return matplotlib_scraper(*args, bbox_inches="tight", **kwargs)
