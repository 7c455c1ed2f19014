//! `dlw daq-info`: what a DAQ file or a tracker log holds, before importing it.
