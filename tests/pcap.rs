//! pcap fixtures (filled below).
