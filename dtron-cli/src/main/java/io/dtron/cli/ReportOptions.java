package io.dtron.cli;

import io.dtron.engine.TestOptions;
import io.dtron.model.Layout;
import io.dtron.model.ModelException;
import io.dtron.model.Network;
import io.dtron.report.LiveView;
import io.dtron.report.ReportPage;
import io.dtron.report.RunRecord;
import io.dtron.report.RunRecorder;
import java.io.IOException;
import java.io.PrintWriter;
import java.net.InetAddress;
import java.nio.file.Path;
import picocli.CommandLine.Option;

/**
 * The report options of {@code dtron run}: {@code --report FILE.html}, the page of the run written at its end, and
 * {@code --live PORT}, the page served while the run goes on (at {@code --bind}, loopback by default).
 */
final class ReportOptions {
    @Option(names = "--report", paramLabel = "FILE.html",
            description = "Write the run's report to FILE: one self-contained HTML page with the verdict, the model"
                    + " drawn with what the run covered and where it ended, the inputs and outputs over time, the"
                    + " delays and the coverage.")
    Path file;

    @Option(names = "--live", paramLabel = "PORT",
            description = "Serve the report while the run goes on at http://ADDR:PORT/ (ADDR: --bind, default"
                    + " loopback; PORT 0: any free port), updated as events happen.")
    Integer port;

    /** Whether a report or a live view was asked for. */
    boolean given() {
        return file != null || port != null;
    }

    /** The problem with the values, or null. */
    String problem() {
        if (port != null && (port < 0 || port > 65535)) {
            return "--live takes a port of 0 to 65535 (0: any free port): " + port;
        }
        Path folder = file == null ? null : file.toAbsolutePath().getParent();
        if (folder != null && !java.nio.file.Files.isDirectory(folder)) {
            return "--report " + file + ": there is no folder " + folder + " to write it in";
        }
        return null;
    }

    /**
     * Starts recording a run of {@code model} (and serving it when {@code --live} says so); null when neither option
     * was given.
     *
     * @throws IOException if the live view cannot listen on its port
     */
    Session open(Path model, Network network, TestOptions options, InetAddress bind, PrintWriter out)
            throws IOException {
        if (!given()) {
            return null;
        }
        Layout layout = null;
        String note = null;
        try {
            layout = Layout.read(model);
        } catch (ModelException e) {
            note = "the model's drawing could not be read: " + e.getMessage().lines().findFirst().orElse("");
        }
        RunRecord record = new RunRecord(model.toString(), network, layout, note);
        record.start(options.seed(), options.timeUnitMicros(), options.timeout(), options.virtualTime());
        LiveView live = null;
        if (port != null) {
            try {
                live = LiveView.start(record, bind, port);
            } catch (IOException e) {
                throw new IOException("--live " + port + ": cannot listen on " + bind.getHostAddress() + ":" + port
                        + ": " + e.getMessage() + " (give another port, or 0 for any free one)", e);
            }
            out.println("dtron run: live view at " + live.url());
            out.flush();
        }
        return new Session(record, live, file);
    }

    /** A run being recorded: its recorder for the tester, the live view, and the page to write at the end. */
    record Session(RunRecord record, LiveView live, Path file) {
        RunRecorder recorder() {
            return new RunRecorder(record);
        }

        /** Ends the live view's streams (after what the browsers have queued) and stops serving. */
        void stopLive() {
            if (live != null) {
                live.close();
            }
        }

        /** Writes the report when one was asked for, saying so, or why it could not. */
        void write(PrintWriter out, PrintWriter err) {
            if (file == null) {
                return;
            }
            try {
                ReportPage.write(record, file);
                out.println("dtron run: report written to " + file);
            } catch (IOException e) {
                err.println("dtron run: cannot write the report " + file + ": " + OutputFile.reason(e));
                err.flush();
            }
            out.flush();
        }
    }
}
