package io.dtron.selenium;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertSame;
import static org.junit.jupiter.api.Assertions.assertThrows;

import io.dtron.api.Dtron;
import io.dtron.api.DtronOptions;
import io.dtron.api.IDtronChannel;
import io.dtron.selenium.sample.Farewell;
import io.dtron.selenium.sample.Greet;
import io.dtron.selenium.sample.Ping;
import io.dtron.selenium.sample.Remember;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.List;
import java.util.UUID;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicInteger;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;

/** Discovery, channels and injection of adapters; browsers started ahead of the run. */
@Timeout(value = 30, unit = TimeUnit.SECONDS)
class SeleniumAdaptersTest {
    private static final String SAMPLE = "io.dtron.selenium.sample";
    private static final WebDriverFactory NO_BROWSER = () -> {
        throw new AssertionError("these tests start no browser");
    };

    @Test
    void scanningFindsTheConcreteAdaptersOfThePackageWithTheirChannels() {
        SeleniumAdapters adapters = SeleniumAdapters.builder().scan(SAMPLE).driverFactory(NO_BROWSER).build();
        assertEquals(List.of("Farewell", "Greet", "Ping", "Press", "Recall", "Remember"),
                adapters.getAdapters().stream().map(a -> a.getClass().getSimpleName()).toList());
        assertEquals(IDtronChannel.of("remember", "user", "value"), adapters.getAdapter(Remember.class).getChannel());
        assertEquals(IDtronChannel.of("greet", "user"), adapters.getAdapter(Greet.class).getChannel());
        assertEquals(IDtronChannel.of("ping"), adapters.getAdapter(Ping.class).getChannel());
    }

    @Test
    void propertiesAreInjectedAndAdaptersAreInjectedIntoEachOther() {
        SeleniumAdapters adapters = SeleniumAdapters.builder().scan(SAMPLE).driverFactory(NO_BROWSER)
                .property("BASE_URL", "http://127.0.0.1:1234").build();
        Greet greet = adapters.getAdapter(Greet.class);
        assertEquals("http://127.0.0.1:1234", greet.baseUrl());
        assertSame(greet, adapters.getAdapter(Farewell.class).greet(), "one instance of each adapter");
    }

    @Test
    void filesOverrideThePackagesPropertiesAndSystemPropertiesOverrideFiles(@TempDir Path dir) throws Exception {
        SeleniumAdapters fromResource = SeleniumAdapters.builder().scan(SAMPLE).driverFactory(NO_BROWSER).build();
        assertEquals("http://127.0.0.1:9", fromResource.getAdapter(Greet.class).baseUrl());

        Path file = dir.resolve("site.properties");
        Files.writeString(file, "BASE_URL=http://127.0.0.1:8001\n");
        SeleniumAdapters fromFile = SeleniumAdapters.builder().scan(SAMPLE).properties(file)
                .driverFactory(NO_BROWSER).build();
        assertEquals("http://127.0.0.1:8001", fromFile.getAdapter(Greet.class).baseUrl());

        System.setProperty("BASE_URL", "http://127.0.0.1:8002");
        try {
            SeleniumAdapters fromSystem = SeleniumAdapters.builder().scan(SAMPLE).properties(file)
                    .driverFactory(NO_BROWSER).build();
            assertEquals("http://127.0.0.1:8002", fromSystem.getAdapter(Greet.class).baseUrl());
        } finally {
            System.clearProperty("BASE_URL");
        }
    }

    @Test
    void aMissingPropertyIsNamed() {
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class,
                () -> SeleniumAdapters.builder().adapter(Greet.class).driverFactory(NO_BROWSER).build());
        assertEquals("cannot create the adapters: No implementation for java.lang.String annotated with"
                + " @com.google.inject.name.Named(\"BASE_URL\") was bound.", e.getMessage());
    }

    @Test
    void theBrowsersPropertySaysHowManyBrowsersStartBeforeTheRun() {
        AtomicInteger started = new AtomicInteger();
        WebDriverFactory counting = () -> {
            started.incrementAndGet();
            return HeadlessChrome.defaults().create();
        };
        try (Dtron bus = Dtron.connect(DtronOptions.builder().clusterName("browsers-" + UUID.randomUUID())
                .inJvm(true).build());
                SeleniumAdapters adapters = SeleniumAdapters.builder().scan(SAMPLE).driverFactory(counting)
                        .property(SeleniumAdapters.BROWSERS_PROPERTY, "2").build()) {
            adapters.start(bus);
            assertEquals(2, started.get(), "users 0 and 1 have their browsers before the first message");
        }
        SeleniumAdapters explicit = SeleniumAdapters.builder().scan(SAMPLE).driverFactory(NO_BROWSER).browsers(0)
                .property(SeleniumAdapters.BROWSERS_PROPERTY, "3").build();
        try (Dtron bus = Dtron.connect(DtronOptions.builder().clusterName("browsers-" + UUID.randomUUID())
                .inJvm(true).build()); explicit) {
            explicit.start(bus);
        }
        IllegalArgumentException bad = assertThrows(IllegalArgumentException.class, () -> SeleniumAdapters.builder()
                .scan(SAMPLE).property(SeleniumAdapters.BROWSERS_PROPERTY, "two").build());
        assertEquals("property dtron.browsers = 'two': give the number of browsers to start before the run (0 or"
                + " more)", bad.getMessage());
    }

    @Test
    void aPackageWithoutAdaptersIsRefused() {
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class,
                () -> new SeleniumAdapters("io.dtron.selenium.internal"));
        assertEquals("no adapters in package io.dtron.selenium.internal: no concrete class there extends"
                + " io.dtron.selenium.AbstractSeleniumAdapter", e.getMessage());
    }

    @Test
    void twoAdaptersOfOneChannelAreRefused() {
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class,
                () -> SeleniumAdapters.builder().adapter(Ping.class).adapter(Greet.class)
                        .adapter(io.dtron.selenium.duplicate.Greet.class).property("BASE_URL", "http://127.0.0.1:9")
                        .build());
        assertEquals("adapters io.dtron.selenium.sample.Greet and io.dtron.selenium.duplicate.Greet both serve"
                + " channel 'greet'", e.getMessage());
    }

    @Test
    void helpersOutsideExecuteSayWhy() {
        SeleniumAdapters adapters = SeleniumAdapters.builder().scan(SAMPLE).driverFactory(NO_BROWSER).build();
        IllegalStateException e = assertThrows(IllegalStateException.class,
                () -> adapters.getAdapter(Greet.class).requireGreeted());
        assertEquals("Greet[greet[user]] is not started: SeleniumAdapters starts it", e.getMessage());
    }
}
