#include "ui/render/movie_writer.hpp"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/error.h>
#include <libavutil/imgutils.h>
#include <libavutil/log.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}

#include <mutex>
#include <stdexcept>

namespace faultline::ui {

namespace {

// libx264 reports its settings and statistics on stderr at the default level: errors only.
void quietLibav() {
    static std::once_flag once;
    std::call_once(once, [] { av_log_set_level(AV_LOG_ERROR); });
}

std::string avError(int code) {
    char text[AV_ERROR_MAX_STRING_SIZE] = {};
    av_strerror(code, text, sizeof text);
    return text;
}

} // namespace

struct MovieWriter::State {
    std::string path;
    MovieSettings settings;
    AVFormatContext* format = nullptr;
    AVCodecContext* codec = nullptr;
    AVStream* stream = nullptr;
    AVFrame* frame = nullptr;
    AVPacket* packet = nullptr;
    SwsContext* scale = nullptr;
    std::int64_t next = 0; // presentation time of the next frame, in frames
    bool headerWritten = false, finished = false;

    [[noreturn]] void fail(const std::string& what, int code) const {
        throw std::runtime_error(path + ": " + what + " (" + avError(code) + ")");
    }

    // Sends one frame (null: flush) and writes every packet the encoder has ready.
    void encode(AVFrame* in) {
        int r = avcodec_send_frame(codec, in);
        if (r < 0)
            fail("cannot encode a video frame", r);
        while ((r = avcodec_receive_packet(codec, packet)) >= 0) {
            av_packet_rescale_ts(packet, codec->time_base, stream->time_base);
            packet->stream_index = stream->index;
            const int w = av_interleaved_write_frame(format, packet);
            av_packet_unref(packet);
            if (w < 0)
                fail("cannot write to the movie", w);
        }
        if (r != AVERROR(EAGAIN) && r != AVERROR_EOF)
            fail("the encoder failed", r);
    }

    ~State() {
        sws_freeContext(scale);
        av_packet_free(&packet);
        av_frame_free(&frame);
        avcodec_free_context(&codec);
        if (format) {
            if (headerWritten && !finished)
                av_write_trailer(format);
            if (!(format->oformat->flags & AVFMT_NOFILE))
                avio_closep(&format->pb);
            avformat_free_context(format);
        }
    }
};

MovieWriter::MovieWriter(const std::string& path, const MovieSettings& settingsIn)
    : m_state(std::make_unique<State>()) {
    quietLibav();
    State& s = *m_state;
    s.path = path;
    s.settings = settingsIn;
    s.settings.width += s.settings.width % 2;
    s.settings.height += s.settings.height % 2;
    if (s.settings.width < 16 || s.settings.height < 16 || s.settings.framesPerSecond < 1)
        throw std::runtime_error(path + ": a movie needs at least 16 x 16 pixels and 1 frame/s");
    int r = avformat_alloc_output_context2(&s.format, nullptr, "mp4", path.c_str());
    if (r < 0 || !s.format)
        s.fail("cannot make an MP4 container", r);
    const AVCodec* encoder = avcodec_find_encoder_by_name("libx264");
    if (!encoder)
        encoder = avcodec_find_encoder(AV_CODEC_ID_H264);
    if (!encoder)
        throw std::runtime_error(path + ": this libavcodec has no H.264 encoder");
    s.stream = avformat_new_stream(s.format, nullptr);
    s.codec = avcodec_alloc_context3(encoder);
    if (!s.stream || !s.codec)
        throw std::runtime_error(path + ": out of memory opening the encoder");
    s.codec->width = s.settings.width;
    s.codec->height = s.settings.height;
    s.codec->pix_fmt = AV_PIX_FMT_YUV420P;
    s.codec->time_base = AVRational{1, s.settings.framesPerSecond};
    s.codec->framerate = AVRational{s.settings.framesPerSecond, 1};
    s.codec->gop_size = 2 * s.settings.framesPerSecond;
    if (s.format->oformat->flags & AVFMT_GLOBALHEADER)
        s.codec->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
    AVDictionary* options = nullptr;
    av_dict_set(&options, "preset", "medium", 0);
    av_dict_set(&options, "crf", std::to_string(s.settings.quality).c_str(), 0);
    r = avcodec_open2(s.codec, encoder, &options);
    av_dict_free(&options);
    if (r < 0)
        s.fail("cannot open the H.264 encoder", r);
    r = avcodec_parameters_from_context(s.stream->codecpar, s.codec);
    if (r < 0)
        s.fail("cannot set the stream's parameters", r);
    s.stream->time_base = s.codec->time_base;
    s.stream->avg_frame_rate = s.codec->framerate;
    if (!(s.format->oformat->flags & AVFMT_NOFILE)) {
        r = avio_open(&s.format->pb, path.c_str(), AVIO_FLAG_WRITE);
        if (r < 0)
            s.fail("cannot open the file for writing", r);
    }
    r = avformat_write_header(s.format, nullptr);
    if (r < 0)
        s.fail("cannot write the MP4 header", r);
    s.headerWritten = true;
    s.frame = av_frame_alloc();
    s.packet = av_packet_alloc();
    if (!s.frame || !s.packet)
        throw std::runtime_error(path + ": out of memory");
    s.frame->format = AV_PIX_FMT_YUV420P;
    s.frame->width = s.settings.width;
    s.frame->height = s.settings.height;
    r = av_frame_get_buffer(s.frame, 0);
    if (r < 0)
        s.fail("cannot allocate a video frame", r);
}

MovieWriter::~MovieWriter() = default;

void MovieWriter::add(const RgbaImage& image) {
    State& s = *m_state;
    if (s.finished)
        throw std::logic_error("MovieWriter::add after finish");
    if (image.width > s.settings.width || image.height > s.settings.height ||
        image.width < s.settings.width - 1 || image.height < s.settings.height - 1)
        throw std::invalid_argument(s.path + ": an image of " + std::to_string(image.width) + "x" +
                                    std::to_string(image.height) + " for a movie of " +
                                    std::to_string(s.settings.width) + "x" +
                                    std::to_string(s.settings.height));
    // An odd-sized image fills the even frame with its last row or column repeated (the
    // scaler stretches it by under a pixel).
    s.scale = sws_getCachedContext(s.scale, image.width, image.height, AV_PIX_FMT_RGBA,
                                   s.settings.width, s.settings.height, AV_PIX_FMT_YUV420P,
                                   SWS_BICUBIC, nullptr, nullptr, nullptr);
    if (!s.scale)
        throw std::runtime_error(s.path + ": cannot convert RGBA to YUV");
    const int r = av_frame_make_writable(s.frame);
    if (r < 0)
        s.fail("cannot write a video frame", r);
    const std::uint8_t* src[1] = {image.pixels.data()};
    const int stride[1] = {image.width * 4};
    sws_scale(s.scale, src, stride, 0, image.height, s.frame->data, s.frame->linesize);
    s.frame->pts = s.next++;
    s.encode(s.frame);
}

void MovieWriter::finish() {
    State& s = *m_state;
    if (s.finished)
        return;
    s.encode(nullptr);
    const int r = av_write_trailer(s.format);
    s.finished = true;
    if (r < 0)
        s.fail("cannot finish the MP4 file", r);
}

std::size_t MovieWriter::framesWritten() const { return static_cast<std::size_t>(m_state->next); }

MovieProbe probeMovie(const std::string& path) {
    quietLibav();
    AVFormatContext* format = nullptr;
    int r = avformat_open_input(&format, path.c_str(), nullptr, nullptr);
    if (r < 0)
        throw std::runtime_error(path + ": cannot open the movie (" + avError(r) + ")");
    struct Close {
        AVFormatContext*& f;
        AVCodecContext* c = nullptr;
        AVPacket* p = nullptr;
        AVFrame* fr = nullptr;
        ~Close() {
            av_frame_free(&fr);
            av_packet_free(&p);
            avcodec_free_context(&c);
            avformat_close_input(&f);
        }
    } close{format};
    r = avformat_find_stream_info(format, nullptr);
    if (r < 0)
        throw std::runtime_error(path + ": cannot read the streams (" + avError(r) + ")");
    const AVCodec* decoder = nullptr;
    const int index = av_find_best_stream(format, AVMEDIA_TYPE_VIDEO, -1, -1, &decoder, 0);
    if (index < 0 || !decoder)
        throw std::runtime_error(path + ": no video stream that can be decoded");
    MovieProbe probe;
    const AVCodecParameters* par = format->streams[index]->codecpar;
    probe.width = par->width;
    probe.height = par->height;
    probe.codec = avcodec_get_name(par->codec_id);
    close.c = avcodec_alloc_context3(decoder);
    close.p = av_packet_alloc();
    close.fr = av_frame_alloc();
    if (!close.c || !close.p || !close.fr || avcodec_parameters_to_context(close.c, par) < 0 ||
        avcodec_open2(close.c, decoder, nullptr) < 0)
        throw std::runtime_error(path + ": cannot open the decoder");
    auto drain = [&] {
        while (avcodec_receive_frame(close.c, close.fr) >= 0)
            ++probe.frames;
    };
    while (av_read_frame(format, close.p) >= 0) {
        if (close.p->stream_index == index && avcodec_send_packet(close.c, close.p) >= 0)
            drain();
        av_packet_unref(close.p);
    }
    avcodec_send_packet(close.c, nullptr);
    drain();
    return probe;
}

} // namespace faultline::ui
