#include "casmap/drivers/telegram_parser.hpp"

namespace casmap::drivers {

TelegramParser::TelegramParser(Sender sender, std::uint8_t address, bool check_follower)
    : sender_(sender),
      address_(address),
      check_follower_(check_follower && sender == Sender::kScanner) {
    frame_.reserve(kMaxFrameBytes);
    replay_.reserve(2 * kMaxFrameBytes);
    telegram_.data.reserve(kMaxLen);
}

void TelegramParser::Feed(std::span<const std::uint8_t> bytes, const Callback& callback) {
    for (const std::uint8_t b : bytes) {
        ++counters_.bytes;
        replay_.push_back(b);
        Drain(callback);
    }
}

void TelegramParser::Idle(const Callback& callback) {
    if (pending_) {
        Deliver(callback);
    }
}

void TelegramParser::Timeout(const Callback& callback) {
    Idle(callback);
    while (!frame_.empty()) {
        ++counters_.timeouts;
        Abandon();
        Drain(callback);
    }
}

void TelegramParser::Reset() {
    frame_.clear();
    replay_.clear();
    replay_pos_ = 0;
    expected_size_ = 0;
    out_of_sync_ = false;
    pending_ = false;
}

void TelegramParser::Drain(const Callback& callback) {
    while (replay_pos_ < replay_.size()) {
        Step(replay_[replay_pos_++], callback);
    }
    replay_.clear();
    replay_pos_ = 0;
}

bool TelegramParser::AddressOk(std::uint8_t address) const {
    if (sender_ == Sender::kScanner) {
        return address == (kReplyAddressBit | address_);
    }
    return address == kHostAddress || address == address_;
}

void TelegramParser::LoseSync() {
    if (!out_of_sync_) {
        out_of_sync_ = true;
        ++counters_.resyncs;
    }
}

void TelegramParser::Abandon() {
    last_rejected_command_ = frame_.size() >= 5 ? frame_[4] : 0;
    // Drop the STX; everything after it is parsed again before any newer byte.
    ++counters_.dropped_bytes;
    LoseSync();
    replay_.insert(replay_.begin() + static_cast<std::ptrdiff_t>(replay_pos_), frame_.begin() + 1,
                   frame_.end());
    frame_.clear();
    expected_size_ = 0;
    pending_ = false;
}

void TelegramParser::Step(std::uint8_t byte, const Callback& callback) {
    if (pending_) {
        if (byte == kStx || byte == kAck || byte == kNak) {
            Deliver(callback);  // then the byte is parsed below as usual
        } else {
            ++counters_.bad_followers;
            last_rejected_command_ = frame_[4];
            callback(ParserEvent::kBadFollower, telegram_);
            frame_.push_back(byte);  // parsed again after the frame's bytes
            Abandon();
            return;
        }
    }
    if (frame_.empty()) {
        if (byte == kStx) {
            frame_.push_back(byte);
        } else if (sender_ == Sender::kScanner && byte == kAck) {
            ++counters_.acks;
            callback(ParserEvent::kAckByte, telegram_);
        } else if (sender_ == Sender::kScanner && byte == kNak) {
            ++counters_.naks;
            callback(ParserEvent::kNakByte, telegram_);
        } else {
            ++counters_.dropped_bytes;
            LoseSync();
        }
        return;
    }
    frame_.push_back(byte);
    if (frame_.size() == 2 && !AddressOk(byte)) {
        ++counters_.bad_headers;
        Abandon();
        return;
    }
    if (frame_.size() == 4) {
        const std::size_t len = frame_[2] | (static_cast<std::size_t>(frame_[3]) << 8U);
        const std::size_t min_len = sender_ == Sender::kScanner ? 2 : 1;
        if (len < min_len || len > kMaxLen) {
            ++counters_.bad_headers;
            Abandon();
            return;
        }
        expected_size_ = len + kFrameOverhead;
        return;
    }
    if (frame_.size() < 4 || frame_.size() < expected_size_) {
        return;
    }
    const std::size_t crc_at = expected_size_ - 2;
    const std::uint16_t crc =
        static_cast<std::uint16_t>(frame_[crc_at] | (frame_[crc_at + 1] << 8U));
    if (Crc16(std::span(frame_).first(crc_at)) != crc) {
        ++counters_.crc_errors;
        last_rejected_command_ = frame_[4];
        callback(ParserEvent::kBadCrc, telegram_);
        Abandon();
        return;
    }
    if (check_follower_) {
        pending_ = true;
        return;
    }
    Deliver(callback);
}

void TelegramParser::Deliver(const Callback& callback) {
    const bool reply = sender_ == Sender::kScanner;
    const std::size_t crc_at = expected_size_ - 2;
    telegram_.address = frame_[1];
    telegram_.command = frame_[4];
    const std::size_t data_end = reply ? crc_at - 1 : crc_at;
    telegram_.data.assign(frame_.begin() + 5,
                          frame_.begin() + static_cast<std::ptrdiff_t>(data_end));
    telegram_.status = reply ? frame_[crc_at - 1] : kStatusOk;
    frame_.clear();
    expected_size_ = 0;
    pending_ = false;
    out_of_sync_ = false;
    ++counters_.telegrams;
    callback(ParserEvent::kTelegram, telegram_);
}

}  // namespace casmap::drivers
